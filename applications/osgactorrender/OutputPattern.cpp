#include "OutputPattern.h"

namespace osgActorRender {

bool OutputPattern::parse(const std::string& pattern, std::string& error)
{
    *this = OutputPattern();
    if (pattern.empty())
    {
        error = "the output pattern is empty";
        return false;
    }
    std::string* target = &_prefix;
    for (size_t i = 0; i < pattern.size(); ++i)
    {
        if (pattern[i] != '%')
        {
            *target += pattern[i];
            continue;
        }
        size_t j = i + 1;
        if (j < pattern.size() && pattern[j] == '%')
        {
            *target += '%';
            i = j;
            continue;
        }
        const bool zeroPad = j < pattern.size() && pattern[j] == '0';
        if (zeroPad) ++j;
        const size_t digits = j;
        while (j < pattern.size() && pattern[j] >= '0' && pattern[j] <= '9') ++j;
        if (j >= pattern.size() || pattern[j] != 'd' || j - digits > 1 || _hasField)
        {
            error = "the output pattern \"" + pattern + "\" may hold one frame number field (%d, %04d) and %% only";
            return false;
        }
        _hasField = true;
        _zeroPad = zeroPad;
        _width = j > digits ? pattern[digits] - '0' : 0;
        target = &_suffix;
        i = j;
    }
    return true;
}

OutputPattern OutputPattern::fromChecked(const std::string& pattern)
{
    OutputPattern parsed;
    std::string unused;
    if (!pattern.empty()) parsed.parse(pattern, unused);
    return parsed;
}

std::string OutputPattern::format(unsigned frame) const
{
    if (!_hasField) return _prefix;
    std::string number = std::to_string(frame);
    if (number.size() < static_cast<size_t>(_width))
        number.insert(0, static_cast<size_t>(_width) - number.size(), _zeroPad ? '0' : ' ');
    return _prefix + number + _suffix;
}

} // namespace osgActorRender
