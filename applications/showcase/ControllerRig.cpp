#include "ControllerRig.h"

#include <osg/NodeVisitor>

#include <algorithm>

namespace osgActorShowcase {

namespace {

/** The actors below a node, not looking inside actors (an actor's skeleton belongs to it). */
class RiggableActorFinder : public osg::NodeVisitor
{
public:
    RiggableActorFinder() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Transform& transform) override
    {
        if (osgActor::ActorNode* actor = dynamic_cast<osgActor::ActorNode*>(&transform)) actors.push_back(actor);
        else traverse(transform);
    }

    std::vector<osgActor::ActorNode*> actors;
};

} // namespace

bool ControllerRig::wasRefused(const osgActor::ActorNode& actor) const
{
    return std::any_of(_refused.begin(), _refused.end(),
                       [&](const osg::observer_ptr<osgActor::ActorNode>& refused) { return refused.get() == &actor; });
}

void ControllerRig::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    if (node)
    {
        RiggableActorFinder finder;
        finder.setTraversalMask(~0u);
        finder.setNodeMaskOverride(~0u);
        node->traverse(finder);
        for (osgActor::ActorNode* actor : finder.actors)
        {
            if (actor->findController(getRigControllerName()) || wasRefused(*actor)) continue;
            if (!rig(*actor)) _refused.push_back(actor);
        }
    }
    traverse(node, nv);
}

} // namespace osgActorShowcase
