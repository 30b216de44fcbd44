#include <osgActor/text/TextLines>

#include <cstdio>

namespace osgActor {

namespace {

/** A byte no text file holds: the C0 controls but tab, line feed and carriage return, and DEL. */
bool isControl(char c)
{
    const unsigned char u = static_cast<unsigned char>(c);
    return (u < 0x20 && c != '\t' && c != '\n' && c != '\r') || u == 0x7f;
}

char lowerAscii(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; }

} // namespace

TextLines::TextLines(std::istream& in, const std::string& fileName) : _fileName(fileName)
{
    // Room for the whole rest of a stream that can tell its length (a file, a string), made at once: a text grown
    // chunk by chunk is copied each time it fills, and a large one maps its memory afresh each time.
    const std::istream::pos_type start = in.tellg();
    if (start != std::istream::pos_type(-1))
    {
        in.seekg(0, std::ios::end);
        const std::istream::pos_type end = in.tellg();
        in.clear();
        in.seekg(start);
        if (end != std::istream::pos_type(-1) && end > start) _text.reserve(static_cast<std::size_t>(end - start));
    }
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0)
        _text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (_text.compare(0, 3, "\xEF\xBB\xBF") == 0) _position = 3; // a UTF-8 byte-order mark
    checkCharacters();
}

void TextLines::checkCharacters()
{
    unsigned line = 1;
    const std::size_t size = _text.size();
    for (std::size_t i = _position; i < size; ++i)
    {
        const char c = _text[i];
        if (c == '\n' || (c == '\r' && (i + 1 == size || _text[i + 1] != '\n'))) ++line;
        else if (isControl(c) && _error.empty())
        {
            char code[8];
            std::snprintf(code, sizeof(code), "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(c)));
            _error = where(line) + "a control character (" + code +
                     ") in the text: names and words hold printable characters only (a binary or damaged file?)";
        }
    }
    _endLineNumber = line;
}

bool TextLines::nextLine()
{
    _tokens.clear();
    _tokenized = false;
    _tokenIndex = 0;
    if (_position >= _text.size()) return false;
    const char* const text = _text.data();
    const std::size_t size = _text.size();
    const std::size_t begin = _position;
    std::size_t i = begin;
    while (i < size && text[i] != '\n' && text[i] != '\r') ++i;
    _line = std::string_view(text + begin, i - begin);
    _position = i;
    if (_position < size) _position += text[i] == '\r' && i + 1 < size && text[i + 1] == '\n' ? 2 : 1;
    ++_lineNumber;
    return true;
}

const std::vector<std::string_view>& TextLines::tokens() const
{
    if (_tokenized) return _tokens;
    _tokenized = true;
    const char* const text = _line.data();
    const std::size_t size = _line.size();
    std::size_t i = 0;
    while (true)
    {
        while (i < size && isBlank(text[i])) ++i;
        if (i >= size) break;
        const std::size_t start = i;
        while (i < size && !isBlank(text[i])) ++i;
        _tokens.emplace_back(text + start, i - start);
    }
    return _tokens;
}

bool TextLines::nextToken(std::string_view& token)
{
    while (_tokenIndex >= tokens().size())
        if (!nextLine()) return false;
    token = _tokens[_tokenIndex++];
    return true;
}

std::string TextLines::restOfLine()
{
    const std::vector<std::string_view>& words = tokens();
    std::string rest;
    for (; _tokenIndex < words.size(); ++_tokenIndex)
    {
        if (!rest.empty()) rest += ' ';
        rest.append(words[_tokenIndex].data(), words[_tokenIndex].size());
    }
    return rest;
}

std::string TextLines::where() const { return where(_lineNumber); }

std::string TextLines::where(unsigned line) const { return _fileName + ":" + std::to_string(line) + ": "; }

bool sameWord(std::string_view token, std::string_view keyword)
{
    if (token.size() != keyword.size()) return false;
    for (std::size_t i = 0; i < token.size(); ++i)
        if (lowerAscii(token[i]) != lowerAscii(keyword[i])) return false;
    return true;
}

} // namespace osgActor
