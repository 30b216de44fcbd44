#include "CountList"

#include <cstdlib>
#include <sstream>

namespace bench {

bool parseCountList(const std::string& text, int largest, std::vector<int>& values)
{
    values.clear();
    std::stringstream stream(text);
    std::string item;
    while (std::getline(stream, item, ','))
    {
        char* end = nullptr;
        const long value = std::strtol(item.c_str(), &end, 10);
        if (item.empty() || *end != '\0' || value < 1 || value > largest) return false;
        values.push_back(static_cast<int>(value));
    }
    return !values.empty();
}

} // namespace bench
