#include <osgActor/Offscreen/RenderFrames>

#include <osg/NodeVisitor>
#include <osgAnimation/BasicAnimationManager>

#include <algorithm>
#include <vector>

namespace osgActor {

namespace {

/** Every BasicAnimationManager among the update callbacks (nested ones too) of every node. */
class AnimationManagerFinder : public osg::NodeVisitor
{
public:
    AnimationManagerFinder() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ALL_CHILDREN) {}

    void apply(osg::Node& node) override
    {
        for (osg::Callback* callback = node.getUpdateCallback(); callback != nullptr;
             callback = callback->getNestedCallback())
        {
            auto* manager = dynamic_cast<osgAnimation::BasicAnimationManager*>(callback);
            if (manager != nullptr && std::find(managers.begin(), managers.end(), manager) == managers.end())
                managers.push_back(manager);
        }
        traverse(node);
    }

    /** In the order the traversal meets them (the same on every run). */
    std::vector<osgAnimation::BasicAnimationManager*> managers;
};

} // namespace

unsigned playOsgAnimations(osg::Node& scene)
{
    AnimationManagerFinder finder;
    scene.accept(finder);
    unsigned numStarted = 0;
    for (osgAnimation::BasicAnimationManager* manager : finder.managers)
    {
        for (const osg::ref_ptr<osgAnimation::Animation>& animation : manager->getAnimationList())
        {
            if (!animation || manager->isPlaying(animation.get())) continue;
            manager->playAnimation(animation.get());
            ++numStarted;
        }
    }
    return numStarted;
}

} // namespace osgActor
