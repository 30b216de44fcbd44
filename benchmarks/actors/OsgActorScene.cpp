#include "BenchHumanoid"
#include "PeerScenes"

#include <osgActor/ActorGroup>
#include <osgActor/ActorNode>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/ClipPlayer>

#include <cmath>

namespace bench {

namespace {

/** The bench clip as an osgActor clip: uniformly sampled like motion capture, one channel per DOF, linear. */
osgActor::ClipPtr humanoidOsgActorClip()
{
    static const osgActor::ClipPtr clip = [] {
        const BenchClip& bench = humanoidClip();
        const std::vector<BenchJoint>& joints = humanoidJoints();
        osgActor::ClipBuilder builder("bench");
        static const char* const rotations[] = {".rx", ".ry", ".rz"};
        static const char* const translations[] = {".tx", ".ty", ".tz"};
        for (unsigned j = 0; j < joints.size(); ++j)
        {
            for (const char* dof : rotations) builder.addChannel(joints[j].name + dof);
            if (j == 0)
                for (const char* dof : translations) builder.addChannel(joints[j].name + dof);
        }
        std::vector<double> values;
        for (unsigned f = 0; f < bench.numFrames; ++f)
            for (unsigned j = 0; j < joints.size(); ++j)
            {
                for (unsigned a = 0; a < 3; ++a) values.push_back(bench.anglesAt(f, j)[a]);
                if (j == 0)
                    for (unsigned a = 0; a < 3; ++a) values.push_back(bench.rootPosition[f * 3 + a]);
            }
        builder.setFrames(bench.framesPerSecond, std::move(values));
        return builder.build().clip;
    }();
    return clip;
}

} // namespace

osg::ref_ptr<osg::Group> makeOsgActorScene(unsigned numActors, Motion motion, unsigned threads)
{
    osg::ref_ptr<osgActor::ActorNode> prototype = new osgActor::ActorNode(humanoidDefinition());
    for (unsigned j = 0; j < prototype->getNumSkeletonNodes(); ++j)
        prototype->getSkeletonNode(j)->addChild(jointBox().get());
    if (motion != Motion::Idle)
    {
        auto controller = std::make_shared<osgActor::ClipPlayer>(humanoidOsgActorClip());
        controller->setPlayMode(osgActor::PlayMode::Loop);
        controller->play();
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
