#include "BenchHumanoid"
#include "PeerScenes"

#include <osgActor/ActorGroup>
#include <osgActor/ActorNode>

#include <cmath>

namespace bench {

namespace {

/** Samples the bench clip linearly into the DOFs its selection drives (DOF order: root rx ry rz tx ty tz, then
  * rx ry rz per joint). */
class BenchClipController : public osgActor::Controller
{
public:
    void update(const osgActor::ControllerContext& context, osgActor::ControllerTarget& target) override
    {
        const BenchClip& clip = humanoidClip();
        const double frame = std::fmod(context.time, clip.duration()) * clip.framesPerSecond;
        const unsigned f0 = static_cast<unsigned>(frame);
        const unsigned f1 = std::min(f0 + 1, clip.numFrames - 1);
        const double alpha = frame - f0;
        unsigned dof = 0;
        for (unsigned j = 0; j < clip.jointCount; ++j)
        {
            const double* a0 = clip.anglesAt(f0, j);
            const double* a1 = clip.anglesAt(f1, j);
            const bool driven = effectiveWeight(dof) > 0.0;
            for (unsigned a = 0; a < 3; ++a, ++dof)
                if (driven) writeDof(target.pose, dof, a0[a] + alpha * (a1[a] - a0[a]));
            if (j != 0) continue;
            for (unsigned a = 0; a < 3; ++a, ++dof)
            {
                const double p0 = clip.rootPosition[f0 * 3 + a], p1 = clip.rootPosition[f1 * 3 + a];
                if (driven) writeDof(target.pose, dof, p0 + alpha * (p1 - p0));
            }
        }
    }
    std::shared_ptr<osgActor::Controller> cloneController() const override
    {
        return std::make_shared<BenchClipController>(*this);
    }
};

} // namespace

osg::ref_ptr<osg::Group> makeOsgActorScene(unsigned numActors, Motion motion, unsigned threads)
{
    osg::ref_ptr<osgActor::ActorNode> prototype = new osgActor::ActorNode(humanoidDefinition());
    for (unsigned j = 0; j < prototype->getNumSkeletonNodes(); ++j)
        prototype->getSkeletonNode(j)->addChild(jointBox().get());
    if (motion != Motion::Idle)
    {
        auto controller = std::make_shared<BenchClipController>();
        if (motion == Motion::Quarter)
            // 8 of 31 joints: the left arm and the neck.
            controller->setSelection(osgActor::DofSelection::joints(
                *prototype->getDefinition(), {"lclavicle", "lowerneck"}, true));
        prototype->addController(controller);
    }
    osg::ref_ptr<osg::Group> scene;
    if (threads > 0)
    {
        osg::ref_ptr<osgActor::ActorGroup> group = new osgActor::ActorGroup;
        group->setNumThreads(threads);
        scene = group;
    }
    else
        scene = new osg::Group;
    for (unsigned a = 0; a < numActors; ++a)
        scene->addChild(osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY));
    return scene;
}

} // namespace bench
