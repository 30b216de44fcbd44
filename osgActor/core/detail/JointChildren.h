/* -*-c++-*- osgActor core: the children of every joint of a skeleton, in one array. GLM-free, plain C++. */
#ifndef OSGACTOR_CORE_DETAIL_JOINTCHILDREN_
#define OSGACTOR_CORE_DETAIL_JOINTCHILDREN_ 1

#include <osgActor/core/Span>

#include <vector>

namespace osgActor {
namespace detail {

/** Each joint's children, from each joint's parent: all of them in one array, each joint's a stretch of it, so that a
  * skeleton of many joints costs two allocations rather than a list per joint. A joint's children come in index
  * order. */
class JointChildren
{
public:
    /** parents[j]: joint j's parent, an index into parents, or negative for a joint without one. */
    explicit JointChildren(const std::vector<int>& parents);

    Span<const unsigned> of(unsigned joint) const
    {
        return Span<const unsigned>(_children.data() + _first[joint], _first[joint + 1] - _first[joint]);
    }

private:
    std::vector<unsigned> _first; // joint j's children are _children[_first[j] .. _first[j + 1])
    std::vector<unsigned> _children;
};

} // namespace detail
} // namespace osgActor

#endif
