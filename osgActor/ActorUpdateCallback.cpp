#include <osgActor/ActorNode>
#include <osgActor/ActorUpdateCallback>

namespace osgActor {

void ActorUpdateCallback::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    if (ActorNode* actor = dynamic_cast<ActorNode*>(node)) actor->update(nv);
    // Skeleton nodes carry no callbacks of their own: only visit the subtree when user callbacks below ask for it.
    if (getNestedCallback() || node->getNumChildrenRequiringUpdateTraversal() > 0) traverse(node, nv);
}

} // namespace osgActor
