#include "ActorDriver.h"

#include <osg/NodeVisitor>

namespace osgActorShowcase {

namespace {

/** The actors below a node, not looking inside actors (an actor's skeleton belongs to it). */
class DrivenActorFinder : public osg::NodeVisitor
{
public:
    DrivenActorFinder() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Transform& transform) override
    {
        if (osgActor::ActorNode* actor = dynamic_cast<osgActor::ActorNode*>(&transform)) actors.push_back(actor);
        else traverse(transform);
    }

    std::vector<osgActor::ActorNode*> actors;
};

} // namespace

void ActorDriver::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    const osg::FrameStamp* stamp = nv ? nv->getFrameStamp() : nullptr;
    if (stamp && node)
    {
        // Searched every frame: actors may arrive later (a ProxyNode or the database pager loads them).
        DrivenActorFinder finder;
        finder.setTraversalMask(~0u);
        finder.setNodeMaskOverride(~0u);
        node->traverse(finder);
        for (osgActor::ActorNode* actor : finder.actors) drive(*actor, stamp->getSimulationTime());
    }
    traverse(node, nv);
}

} // namespace osgActorShowcase
