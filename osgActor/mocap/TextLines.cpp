#include <osgActor/mocap/TextLines>

#include <cctype>
#include <charconv>
#include <cmath>

namespace osgActor {

TextLines::TextLines(std::istream& in, const std::string& fileName) : _fileName(fileName)
{
    char buffer[1 << 16];
    while (in.read(buffer, sizeof(buffer)) || in.gcount() > 0) _text.append(buffer, static_cast<std::size_t>(in.gcount()));
}

bool TextLines::nextLine()
{
    _tokens.clear();
    _tokenIndex = 0;
    if (_position >= _text.size()) return false;
    const std::size_t end = _text.find_first_of("\r\n", _position);
    const std::size_t lineEnd = end == std::string::npos ? _text.size() : end;
    _line = std::string_view(_text).substr(_position, lineEnd - _position);
    _position = lineEnd;
    if (_position < _text.size() && _text[_position] == '\r') ++_position;
    if (_position < _text.size() && _text[_position] == '\n') ++_position;
    ++_lineNumber;

    std::size_t i = 0;
    while (i < _line.size())
    {
        while (i < _line.size() && (_line[i] == ' ' || _line[i] == '\t' || _line[i] == '\f' || _line[i] == '\v')) ++i;
        const std::size_t start = i;
        while (i < _line.size() && !(_line[i] == ' ' || _line[i] == '\t' || _line[i] == '\f' || _line[i] == '\v')) ++i;
        if (i > start) _tokens.push_back(_line.substr(start, i - start));
    }
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

bool parseNumber(std::string_view token, double& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    const std::from_chars_result result = std::from_chars(token.data(), token.data() + token.size(), value);
    return result.ec == std::errc() && result.ptr == token.data() + token.size() && std::isfinite(value);
}

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
