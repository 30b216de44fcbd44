#include "ActorFinder.h"

#include <algorithm>

namespace osgActorViewer {

namespace {

class ActorCollector : public osg::NodeVisitor
{
public:
    ActorCollector() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Transform& transform) override
    {
        if (osgActor::ActorNode* actor = dynamic_cast<osgActor::ActorNode*>(&transform))
            if (std::find(actors.begin(), actors.end(), actor) == actors.end()) actors.push_back(actor);
        traverse(transform);
    }

    std::vector<osg::ref_ptr<osgActor::ActorNode>> actors;
};

} // namespace

std::vector<osg::ref_ptr<osgActor::ActorNode>> findActors(osg::Node& root)
{
    ActorCollector collector;
    // Hidden parts hold actors too; TRAVERSE_ALL_CHILDREN and a node mask that matches everything find them.
    collector.setTraversalMask(~0u);
    collector.setNodeMaskOverride(~0u);
    root.accept(collector);
    return collector.actors;
}

} // namespace osgActorViewer
