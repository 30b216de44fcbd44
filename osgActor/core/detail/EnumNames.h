// Internal to the library (not installed, NOT API): an enum's words in the file formats, looked up both ways.
#ifndef OSGACTOR_CORE_DETAIL_ENUMNAMES_H
#define OSGACTOR_CORE_DETAIL_ENUMNAMES_H 1

#include <cstddef>
#include <string>

namespace osgActor {

/** Finds text among the names of an enum's values, given in the enum's order (value i is names[i]); false, value
  * untouched, if it is none of them. */
template <class Enum, std::size_t N>
bool parseEnumName(const char* const (&names)[N], const std::string& text, Enum& value)
{
    for (std::size_t i = 0; i < N; ++i)
        if (text == names[i])
        {
            value = static_cast<Enum>(i);
            return true;
        }
    return false;
}

} // namespace osgActor

#endif
