#include "BenchHumanoid"
#include "PeerScenes"

#include <osg/ShapeDrawable>
#include <osgAnimation/BasicAnimationManager>
#include <osgAnimation/Bone>
#include <osgAnimation/Skeleton>
#include <osgAnimation/StackedQuaternionElement>
#include <osgAnimation/StackedTranslateElement>
#include <osgAnimation/UpdateBone>

#include <vector>

namespace bench {

namespace {

osg::ref_ptr<osg::Group> makeOneOsgAnimationHumanoid()
{
    const std::vector<BenchJoint>& joints = humanoidJoints();
    const BenchClip& clip = humanoidClip();
    osg::ref_ptr<osg::Geode> box = jointBox();

    osg::ref_ptr<osgAnimation::Skeleton> skeleton = new osgAnimation::Skeleton;
    skeleton->setDefaultUpdateCallback();
    std::vector<osgAnimation::Bone*> bones;
    osg::ref_ptr<osgAnimation::Animation> animation = new osgAnimation::Animation;
    animation->setName("clip");
    for (unsigned j = 0; j < joints.size(); ++j)
    {
        const BenchJoint& joint = joints[j];
        osgAnimation::Bone* bone = new osgAnimation::Bone(joint.name);
        bone->setDefaultUpdateCallback();
        osgAnimation::UpdateBone* update = dynamic_cast<osgAnimation::UpdateBone*>(bone->getUpdateCallback());
        const osg::Vec3 offset(joint.offset[0], joint.offset[1], joint.offset[2]);
        update->getStackedTransforms().push_back(new osgAnimation::StackedTranslateElement("translate", offset));
        update->getStackedTransforms().push_back(new osgAnimation::StackedQuaternionElement("quaternion"));
        if (joint.parent < 0) skeleton->addChild(bone);
        else bones[static_cast<unsigned>(joint.parent)]->addChild(bone);
        bones.push_back(bone);

        osg::ref_ptr<osgAnimation::QuatSphericalLinearChannel> rotation = new osgAnimation::QuatSphericalLinearChannel;
        rotation->setName("quaternion");
        rotation->setTargetName(joint.name);
        osgAnimation::QuatKeyframeContainer* keys = rotation->getOrCreateSampler()->getOrCreateKeyframeContainer();
        for (unsigned f = 0; f < clip.numFrames; ++f)
            keys->push_back(osgAnimation::QuatKeyframe(f / clip.framesPerSecond, eulerXYZ(clip.anglesAt(f, j))));
        animation->addChannel(rotation.get());
        if (joint.parent < 0)
        {
            osg::ref_ptr<osgAnimation::Vec3LinearChannel> travel = new osgAnimation::Vec3LinearChannel;
            travel->setName("translate");
            travel->setTargetName(joint.name);
            osgAnimation::Vec3KeyframeContainer* tkeys = travel->getOrCreateSampler()->getOrCreateKeyframeContainer();
            for (unsigned f = 0; f < clip.numFrames; ++f)
            {
                const double* p = &clip.rootPosition[f * 3];
                tkeys->push_back(osgAnimation::Vec3Keyframe(f / clip.framesPerSecond,
                                                            offset + osg::Vec3(p[0], p[1], p[2])));
            }
            animation->addChannel(travel.get());
        }
    }
    // Geometry after the child bones: osgAnimation needs a bone's child bones first to update in order.
    for (osgAnimation::Bone* bone : bones) bone->addChild(box.get());
    animation->setPlayMode(osgAnimation::Animation::LOOP);
    animation->computeDuration();

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(skeleton.get());
    osg::ref_ptr<osgAnimation::BasicAnimationManager> manager = new osgAnimation::BasicAnimationManager;
    manager->registerAnimation(animation.get());
    root->setUpdateCallback(manager.get());
    return root;
}

} // namespace

osg::ref_ptr<osg::Group> makeOsgAnimationScene(unsigned numActors)
{
    osg::ref_ptr<osg::Group> prototype = makeOneOsgAnimationHumanoid();
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    for (unsigned a = 0; a < numActors; ++a)
    {
        // osgAnimation binds channels to the UpdateBone callbacks of one subgraph, so each instance is a deep copy
        // with its own manager, animations and callbacks; the geometry is shared.
        osg::ref_ptr<osg::Group> instance = static_cast<osg::Group*>(prototype->clone(
            osg::CopyOp::DEEP_COPY_NODES | osg::CopyOp::DEEP_COPY_CALLBACKS | osg::CopyOp::DEEP_COPY_OBJECTS));
        osgAnimation::BasicAnimationManager* manager =
            dynamic_cast<osgAnimation::BasicAnimationManager*>(instance->getUpdateCallback());
        manager->playAnimation(manager->getAnimationList().front().get());
        scene->addChild(instance.get());
    }
    return scene;
}

} // namespace bench
