#include <osgActor/ActorNode>
#include <osgActor/ActorUpdateCallback>

#include <typeinfo>

namespace osgActor {

namespace {

/** dynamic_cast, with the common case first: comparing the exact type costs a few instructions, where a
  * dynamic_cast walks the class hierarchy, a large share of an idle actor's update (docs/performance-history.md). */
ActorNode* asActorNode(osg::Node* node) // not null
{
    if (typeid(*node) == typeid(ActorNode)) return static_cast<ActorNode*>(node);
    return dynamic_cast<ActorNode*>(node); // a subclass, or not an actor at all
}

} // namespace

void ActorUpdateCallback::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    if (!node) return;
    if (ActorNode* actor = asActorNode(node)) actor->update(nv);
    // Skeleton nodes carry no callbacks of their own: only visit the subtree when user callbacks below ask for it.
    if (getNestedCallback() || node->getNumChildrenRequiringUpdateTraversal() > 0) traverse(node, nv);
}

} // namespace osgActor
