#include <osgActor/core/detail/NameIndex>

#include <functional>

namespace osgActor {

namespace {

std::uint64_t hashOf(std::string_view name) { return static_cast<std::uint64_t>(std::hash<std::string_view>()(name)); }

/** The hash bits a slot keeps beside the place: enough that two names whose hashes differ seldom share them. */
std::uint64_t hashTag(std::uint64_t hash) { return hash & 0xffffffff00000000ull; }

} // namespace

void NameIndex::build(const std::vector<std::string>& names)
{
    // A power of two at least twice the count: probing stays short and a slot is found by masking.
    std::size_t size = 2;
    while (size < 2 * names.size()) size *= 2;
    _slots.assign(size, 0);
    const std::size_t mask = size - 1;
    for (std::size_t place = 0; place < names.size(); ++place)
    {
        const std::uint64_t hash = hashOf(names[place]);
        std::size_t slot = static_cast<std::size_t>(hash) & mask;
        while (_slots[slot] != 0) slot = (slot + 1) & mask;
        _slots[slot] = hashTag(hash) | static_cast<std::uint64_t>(place + 1);
    }
}

int NameIndex::find(std::string_view name, const std::vector<std::string>& names) const
{
    if (_slots.empty()) return -1;
    const std::uint64_t hash = hashOf(name), tag = hashTag(hash);
    const std::size_t mask = _slots.size() - 1;
    for (std::size_t slot = static_cast<std::size_t>(hash) & mask; _slots[slot] != 0; slot = (slot + 1) & mask)
    {
        const std::uint64_t entry = _slots[slot];
        if ((entry & 0xffffffff00000000ull) != tag) continue;
        const std::size_t place = static_cast<std::size_t>(entry & 0xffffffffull) - 1;
        if (names[place] == name) return static_cast<int>(place);
    }
    return -1;
}

} // namespace osgActor
