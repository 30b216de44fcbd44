#include <osgActor/mocap/TextLines>

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>

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

namespace {

/** Exact powers of ten up to 1e22, the largest a double holds exactly. */
const double kPowersOfTen[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                               1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

/** Clinger's fast path: a decimal whose digits fit in 53 bits, scaled by at most 10^22, is one correctly rounded
  * multiplication or division of two exact doubles, so the result equals strtod's. Mocap numbers ("-0.000000",
  * "27.973049", ".0083333", "1e-014") nearly all take it; false sends the rest to std::from_chars. */
bool parseDecimalFast(std::string_view token, double& value)
{
    const char* p = token.data();
    const char* const end = p + token.size();
    const bool negative = p != end && *p == '-';
    if (negative) ++p;
    std::uint64_t mantissa = 0;
    int digits = 0;   // significant digits kept in mantissa
    int exponent = 0; // power of ten to apply
    bool any = false;
    for (; p != end && *p >= '0' && *p <= '9'; ++p, any = true)
    {
        if (mantissa == 0 && *p == '0') continue; // leading zeros are not significant
        if (++digits > 19) return false;
        mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
    }
    if (p != end && *p == '.')
    {
        for (++p; p != end && *p >= '0' && *p <= '9'; ++p, any = true)
        {
            --exponent;
            if (mantissa == 0 && *p == '0') continue;
            if (++digits > 19) return false;
            mantissa = mantissa * 10 + static_cast<unsigned>(*p - '0');
        }
    }
    if (!any) return false;
    if (p != end && (*p == 'e' || *p == 'E'))
    {
        ++p;
        const bool negativeExponent = p != end && *p == '-';
        if (p != end && (*p == '-' || *p == '+')) ++p;
        if (p == end) return false;
        int written = 0;
        for (; p != end && *p >= '0' && *p <= '9'; ++p)
        {
            if (written > 1000) return false;
            written = written * 10 + (*p - '0');
        }
        exponent += negativeExponent ? -written : written;
    }
    if (p != end) return false;
    if (mantissa > (std::uint64_t(1) << 53) || exponent < -22 || exponent > 22)
        return mantissa == 0 ? (value = negative ? -0.0 : 0.0, true) : false;
    const double m = static_cast<double>(mantissa);
    value = exponent < 0 ? m / kPowersOfTen[-exponent] : m * kPowersOfTen[exponent];
    if (negative) value = -value;
    return true;
}

} // namespace

bool parseNumberToken(std::string_view token, double& value)
{
    if (!token.empty() && token.front() == '+') token.remove_prefix(1);
    if (token.empty()) return false;
    if (parseDecimalFast(token, value)) return true;
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
