#include <osgActor/core/detail/JointChildren.h>

namespace osgActor {
namespace detail {

JointChildren::JointChildren(const std::vector<int>& parents) : _first(parents.size() + 1, 0)
{
    // Count each joint's children, turn the counts into where each joint's stretch starts, then fill the stretches.
    const std::size_t n = parents.size();
    for (std::size_t j = 0; j < n; ++j)
        if (parents[j] >= 0) ++_first[static_cast<std::size_t>(parents[j]) + 1];
    for (std::size_t j = 0; j < n; ++j) _first[j + 1] += _first[j];
    _children.resize(_first[n]);
    std::vector<unsigned> next(_first.begin(), _first.end() - 1);
    for (std::size_t j = 0; j < n; ++j)
        if (parents[j] >= 0) _children[next[static_cast<std::size_t>(parents[j])]++] = static_cast<unsigned>(j);
}

} // namespace detail
} // namespace osgActor
