#include <osgActor/detail/OwnBounds.h>

#include <osgActor/ActorNode>
#include <osgActor/detail/PlacedSkeletonNode.h>

#include <typeinfo>

namespace osgActor {
namespace detail {

namespace {

/** Reads osg::Node's lazy-bound flag, which OSG keeps protected (a pointer to the member, taken in a class derived
  * from osg::Node, applies to any node). */
struct BoundFlag : osg::Node
{
    static bool computed(const osg::Node& node)
    {
        const bool osg::Node::*const flag = &BoundFlag::_boundingSphereComputed;
        return node.*flag;
    }
};

/** Whether a node's bound computation writes nothing shared: no callback computes it and it has one parent. */
bool isSolelyHeld(const osg::Node& node) { return !node.getComputeBoundingSphereCallback() && node.getNumParents() == 1; }

/** The skeleton node of the actor's that child is, of a class whose bound osgActor computes; else null. */
const SkeletonNode* ownJoint(const ActorNode& actor, const osg::Node& child)
{
    const std::type_info& type = typeid(child);
    if (type != typeid(SkeletonNode) && type != typeid(PlacedSkeletonNode)) return nullptr;
    const SkeletonNode& joint = static_cast<const SkeletonNode&>(child);
    const unsigned index = joint.getJointIndex();
    if (index >= actor.getNumSkeletonNodes() || actor.getSkeletonNode(index) != &joint) return nullptr;
    return isSolelyHeld(joint) ? &joint : nullptr;
}

/** Whether every child of group whose bound is not computed yet is a skeleton node of the actor's, solely held,
  * the same holding below it. */
bool dirtyBoundsBelowAreOwn(const ActorNode& actor, const osg::Group& group)
{
    const unsigned numChildren = group.getNumChildren();
    for (unsigned i = 0; i < numChildren; ++i)
    {
        const osg::Node& child = *group.getChild(i);
        if (BoundFlag::computed(child)) continue;
        const SkeletonNode* joint = ownJoint(actor, child);
        if (!joint || !dirtyBoundsBelowAreOwn(actor, *joint)) return false;
    }
    return true;
}

} // namespace

bool computeOwnBound(ActorNode& actor)
{
    if (BoundFlag::computed(actor)) return true;
    if (typeid(actor) != typeid(ActorNode) || !isSolelyHeld(actor) || !dirtyBoundsBelowAreOwn(actor, actor))
        return false;
    actor.getBound();
    return true;
}

} // namespace detail
} // namespace osgActor
