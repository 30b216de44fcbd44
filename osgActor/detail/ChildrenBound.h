// Internal to the library (not installed, NOT API): osg::Group::computeBound()'s union of a node's children, bit for
// bit, for the transforms an actor moves every frame (its translating root joint, the actor itself), whose bounds are
// computed again at every frame while their children's stay as they were. OSG's union visits the children twice
// (a box about their spheres, then the radius about the box's centre), asking each child twice, through a virtual
// call, whether it is a transform; this visits them once, holding where each counting child's sphere is for the
// arithmetic, and lets the caller note what it needs of each child transform in the same visit. The spheres, the
// order they are taken in and the float operations (OSG's inline BoundingBox and BoundingSphere code's, the box's
// sides four lanes at a time) are OSG's, so the union is the same, bit for bit (tests/nodes/test_children_bound.cpp
// compares them after every edit a user can make to the children): it is a function of the counting children's
// spheres, in order, and of nothing else.
#ifndef OSGACTOR_DETAIL_CHILDRENBOUND_H
#define OSGACTOR_DETAIL_CHILDRENBOUND_H 1

#include <osg/BoundingBox>
#include <osg/BoundingSphere>
#include <osg/Group>
#include <osg/Transform>

#include <cstddef>

namespace osgActor {
namespace detail {

/** The spheres osg::Group::computeBound() takes the union of (those of the children that are not transforms or are
  * transforms in their parent's frame), in order, where they are: in the children, which hold them while the union
  * is taken. Only the first kHeld are held; count says how many there are. */
struct CountingSpheres
{
    static constexpr std::size_t kHeld = 8;
    const osg::BoundingSphere* at[kHeld];
    std::size_t count = 0;

    bool allHeld() const { return count <= kHeld; }
};

/** Visits the children once, in order: computes the bound of each that counts (as osg::Group::computeBound() does,
  * through getBound()) and holds where it is, and calls eachTransform(const osg::Transform&) for every child that is
  * a transform, after that. */
template <typename EachTransform>
void gatherCountingSpheres(const osg::NodeList& children, CountingSpheres& spheres, EachTransform&& eachTransform)
{
    spheres.count = 0;
    for (const osg::ref_ptr<osg::Node>& child : children)
    {
        const osg::Transform* transform = child->asTransform();
        if (!transform || transform->getReferenceFrame() == osg::Transform::RELATIVE_RF)
        {
            const osg::BoundingSphere& sphere = child->getBound();
            if (spheres.count < CountingSpheres::kHeld) spheres.at[spheres.count] = &sphere;
            ++spheres.count;
        }
        if (transform) eachTransform(*transform);
    }
}

/** osg::Group::computeBound()'s union of the held spheres (spheres.allHeld()): a box about them, then the radius
  * about its centre, in OSG's arithmetic (ChildrenBound.cpp). */
osg::BoundingSphere unionOfHeld(const CountingSpheres& spheres);

/** osg::Group::computeBound() of a group with these children, visiting them twice as OSG does (for more counting
  * children than CountingSpheres holds); their bounds are computed already. */
osg::BoundingSphere unionOfChildren(const osg::NodeList& children);

/** osg::Group::computeBound() of a group whose children are children (a subclass passes its _children: reading them
  * through osg::Group's public API is a call into the library per child), in one visit where the counting children
  * are few, with eachTransform as gatherCountingSpheres() calls it. */
template <typename EachTransform>
osg::BoundingSphere childrenBound(const osg::NodeList& children, EachTransform&& eachTransform)
{
    CountingSpheres spheres;
    gatherCountingSpheres(children, spheres, eachTransform);
    return spheres.allHeld() ? unionOfHeld(spheres) : unionOfChildren(children);
}

/** The same, noting nothing of the children. */
inline osg::BoundingSphere childrenBound(const osg::NodeList& children)
{
    return childrenBound(children, [](const osg::Transform&) {});
}

} // namespace detail
} // namespace osgActor

#endif
