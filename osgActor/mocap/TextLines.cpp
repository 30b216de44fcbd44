#include <osgActor/mocap/TextLines>

#include <cctype>
#include <charconv>

namespace osgActor {

TextLines::TextLines(std::istream& in, const std::string& fileName) : _fileName(fileName)
{
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0)
        _text.append(buffer, static_cast<std::size_t>(in.gcount()));
}

bool TextLines::nextLine()
{
    _tokens.clear();
    _tokenIndex = 0;
    if (_position >= _text.size()) return false;
    // One pass over the line's characters finds its tokens and its end (the hot loop of every parser).
    const char* const text = _text.data();
    const std::size_t size = _text.size();
    const std::size_t begin = _position;
    std::size_t i = begin;
    while (true)
    {
        while (i < size && (text[i] == ' ' || text[i] == '\t' || text[i] == '\f' || text[i] == '\v')) ++i;
        if (i >= size || text[i] == '\n' || text[i] == '\r') break;
        const std::size_t start = i;
        while (i < size && text[i] != ' ' && text[i] != '\t' && text[i] != '\n' && text[i] != '\r' && text[i] != '\f' &&
               text[i] != '\v')
            ++i;
        _tokens.emplace_back(text + start, i - start);
    }
    _line = std::string_view(text + begin, i - begin);
    _position = i;
    if (_position < size && text[_position] == '\r') ++_position;
    if (_position < size && text[_position] == '\n') ++_position;
    ++_lineNumber;
    return true;
}

bool TextLines::nextToken(std::string_view& token)
{
    while (_tokenIndex >= _tokens.size())
        if (!nextLine()) return false;
    token = _tokens[_tokenIndex++];
    return true;
}

std::string TextLines::restOfLine()
{
    std::string rest;
    for (; _tokenIndex < _tokens.size(); ++_tokenIndex)
    {
        if (!rest.empty()) rest += ' ';
        rest.append(_tokens[_tokenIndex].data(), _tokens[_tokenIndex].size());
    }
    return rest;
}

std::string TextLines::where() const { return where(_lineNumber); }

std::string TextLines::where(unsigned line) const { return _fileName + ":" + std::to_string(line) + ": "; }

bool parseCount(std::string_view token, unsigned long& value)
{
    if (token.empty()) return false;
    const std::from_chars_result result = std::from_chars(token.data(), token.data() + token.size(), value);
    return result.ec == std::errc() && result.ptr == token.data() + token.size();
}

bool sameWord(std::string_view token, std::string_view keyword)
{
    if (token.size() != keyword.size()) return false;
    for (std::size_t i = 0; i < token.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(token[i])) != std::tolower(static_cast<unsigned char>(keyword[i])))
            return false;
    return true;
}

} // namespace osgActor
