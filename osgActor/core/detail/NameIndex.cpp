#include <osgActor/core/detail/NameIndex>

#include <functional>

namespace osgActor {

std::uint64_t NameIndex::hashOf(std::string_view name)
{
    return static_cast<std::uint64_t>(std::hash<std::string_view>()(name));
}

void NameIndex::clear(std::size_t count)
{
    std::size_t size = 2;
    while (size < 2 * count) size *= 2;
    _slots.assign(size, 0);
}

} // namespace osgActor
