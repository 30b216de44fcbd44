#include "BenchHumanoid"
#include "PeerScenes"

#include <osgActor/ActorGroup>
#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/core/ClipPlayer>

#include <cmath>

namespace bench {

osg::ref_ptr<osg::Group> makeOsgActorScene(unsigned numActors, Motion motion, unsigned threads, Bounds bounds)
{
    OsgActorCrowd crowd;
    crowd.motion = motion;
    crowd.threads = threads;
    crowd.bounds = bounds;
    return makeOsgActorScene(numActors, crowd);
}

osg::ref_ptr<osg::Group> makeOsgActorScene(unsigned numActors, const OsgActorCrowd& crowd)
{
    const Motion motion = crowd.motion;
    const unsigned threads = crowd.threads;
    const Bounds bounds = crowd.bounds;
    osg::ref_ptr<osgActor::ActorNode> prototype = new osgActor::ActorNode(humanoidDefinition());
    for (unsigned j = 0; j < prototype->getNumSkeletonNodes(); ++j)
        prototype->getSkeletonNode(j)->addChild(jointBox().get());
    if (crowd.props)
    {
        osg::ref_ptr<osg::Group> prop = new osg::Group; // shared by the clones, as a jointBox() is
        prop->addChild(jointBox().get());
        prototype->getSkeletonNode("rhand")->addChild(prop.get());
    }
    prototype->setBoundMode(bounds == Bounds::FollowPose ? osgActor::ActorNode::BOUND_FOLLOWS_POSE
                                                         : osgActor::ActorNode::BOUND_COVERS_ROTATIONS);
    prototype->setCullMode(crowd.cullNodeByNode ? osgActor::ActorNode::CULL_NODE_BY_NODE
                                                : osgActor::ActorNode::CULL_AS_ONE);
    osgActor::ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = crowd.onlyWhenSeen;
    prototype->setUpdatePolicy(policy);
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
    if (crowd.instanced)
    {
        osg::ref_ptr<osgActor::InstancedActorGroup> group = new osgActor::InstancedActorGroup;
        group->setNumThreads(threads > 0 ? threads : 1);
        scene = group;
    }
    else if (threads > 0)
    {
        osg::ref_ptr<osgActor::ActorGroup> group = new osgActor::ActorGroup;
        group->setNumThreads(threads);
        scene = group;
    }
    else
        scene = new osg::Group;
    for (unsigned a = 0; a < numActors; ++a)
    {
        osg::ref_ptr<osgActor::ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        if (outOfView(a, crowd.outOfView)) actor->setPreTranslation(outOfViewPosition());
        scene->addChild(actor.get());
    }
    return scene;
}

} // namespace bench
