// osgactor_make_test_scenes <folder>: writes the scenes the render tests use as .osgt files, none of them an actor:
//   animation_path.osgt        a box driven round a circle by an osg::AnimationPathCallback, over a floor
//   osganimation.osgt          a box moved and turned by osgAnimation (an UpdateMatrixTransform and a
//                              BasicAnimationManager holding one animation), over a floor
//   particles.osgt             osgParticle: an emitter drawing its rate, positions and speeds from std::rand()
//   two_boxes.osgt             two white boxes side by side, the left one (longer) turning on an AnimationPath
//   two_boxes_changed.osgt     the same with the right box red: the deliberately changed scene
// tests/render/scenes/ holds what this program writes (the test render_test_scenes_are_up_to_date checks it).
#include <osg/AnimationPath>
#include <osg/Geode>
#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osgAnimation/BasicAnimationManager>
#include <osgAnimation/Channel>
#include <osgAnimation/StackedRotateAxisElement>
#include <osgAnimation/StackedTranslateElement>
#include <osgAnimation/UpdateMatrixTransform>
#include <osgDB/WriteFile>
#include <osgParticle/AccelOperator>
#include <osgParticle/ModularEmitter>
#include <osgParticle/ModularProgram>
#include <osgParticle/ParticleSystem>
#include <osgParticle/ParticleSystemUpdater>
#include <osgParticle/RadialShooter>
#include <osgParticle/RandomRateCounter>
#include <osgParticle/SectorPlacer>

#include <cmath>
#include <iostream>
#include <string>

namespace {

osg::ref_ptr<osg::Geode> box(const osg::Vec3& center, const osg::Vec3& halfLengths, const osg::Vec4& colour)
{
    osg::ref_ptr<osg::ShapeDrawable> drawable =
        new osg::ShapeDrawable(new osg::Box(center, 2.0f * halfLengths.x(), 2.0f * halfLengths.y(),
                                            2.0f * halfLengths.z()));
    drawable->setColor(colour);
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(drawable.get());
    return geode;
}

osg::ref_ptr<osg::Geode> floor()
{
    return box(osg::Vec3(0, 0, -0.05f), osg::Vec3(3, 3, 0.05f), osg::Vec4(0.75f, 0.8f, 0.7f, 1));
}

/** A loop round the z axis, radius metres from it, once every period seconds, the box turned along its way. */
osg::ref_ptr<osg::AnimationPath> circlePath(double period, double radius)
{
    osg::ref_ptr<osg::AnimationPath> path = new osg::AnimationPath;
    path->setLoopMode(osg::AnimationPath::LOOP);
    for (int i = 0; i <= 8; ++i)
    {
        const double angle = osg::PI * 2.0 * i / 8.0;
        const osg::Vec3d position(radius * std::cos(angle), radius * std::sin(angle), 0.5);
        path->insert(period * i / 8.0,
                     osg::AnimationPath::ControlPoint(position, osg::Quat(angle, osg::Vec3d(0, 0, 1))));
    }
    return path;
}

osg::ref_ptr<osg::Node> animationPathScene()
{
    osg::ref_ptr<osg::MatrixTransform> mover = new osg::MatrixTransform;
    mover->addChild(box(osg::Vec3(), osg::Vec3(0.4f, 0.25f, 0.5f), osg::Vec4(0.9f, 0.6f, 0.2f, 1)).get());
    mover->setUpdateCallback(new osg::AnimationPathCallback(circlePath(2.0, 1.5).get()));
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(floor().get());
    root->addChild(mover.get());
    return root;
}

osg::ref_ptr<osg::Node> osgAnimationScene()
{
    osg::ref_ptr<osg::MatrixTransform> mover = new osg::MatrixTransform;
    mover->setName("mover");
    mover->addChild(box(osg::Vec3(), osg::Vec3(0.5f, 0.3f, 0.3f), osg::Vec4(0.3f, 0.6f, 0.9f, 1)).get());
    osg::ref_ptr<osgAnimation::UpdateMatrixTransform> update = new osgAnimation::UpdateMatrixTransform("mover");
    update->getStackedTransforms().push_back(new osgAnimation::StackedTranslateElement("position"));
    update->getStackedTransforms().push_back(
        new osgAnimation::StackedRotateAxisElement("turn", osg::Vec3(0, 0, 1), 0.0));
    mover->setUpdateCallback(update.get());

    // Over 2 s, looping: from the left to the right and back, turning one full turn.
    osg::ref_ptr<osgAnimation::Vec3LinearChannel> position = new osgAnimation::Vec3LinearChannel;
    position->setName("position");
    position->setTargetName("mover");
    auto* positions = position->getOrCreateSampler()->getOrCreateKeyframeContainer();
    positions->push_back(osgAnimation::Vec3Keyframe(0.0, osg::Vec3(-2, 0, 0.3f)));
    positions->push_back(osgAnimation::Vec3Keyframe(1.0, osg::Vec3(2, 0, 1.2f)));
    positions->push_back(osgAnimation::Vec3Keyframe(2.0, osg::Vec3(-2, 0, 0.3f)));
    osg::ref_ptr<osgAnimation::FloatLinearChannel> turn = new osgAnimation::FloatLinearChannel;
    turn->setName("turn");
    turn->setTargetName("mover");
    auto* angles = turn->getOrCreateSampler()->getOrCreateKeyframeContainer();
    angles->push_back(osgAnimation::FloatKeyframe(0.0, 0.0f));
    angles->push_back(osgAnimation::FloatKeyframe(2.0, float(2.0 * osg::PI)));
    osg::ref_ptr<osgAnimation::Animation> animation = new osgAnimation::Animation;
    animation->setName("shuttle");
    animation->setPlayMode(osgAnimation::Animation::LOOP);
    animation->addChannel(position.get());
    animation->addChannel(turn.get());

    osg::ref_ptr<osgAnimation::BasicAnimationManager> manager = new osgAnimation::BasicAnimationManager;
    manager->registerAnimation(animation.get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->setUpdateCallback(manager.get());
    root->addChild(floor().get());
    root->addChild(mover.get());
    return root;
}

osg::ref_ptr<osg::Node> particleScene()
{
    osg::ref_ptr<osgParticle::ParticleSystem> particles = new osgParticle::ParticleSystem;
    // No texture (nothing to find on disk), emissive, unlit.
    particles->setDefaultAttributes("", true, false);
    osgParticle::Particle& prototype = particles->getDefaultParticleTemplate();
    prototype.setLifeTime(1.5);
    prototype.setSizeRange(osgParticle::rangef(0.15f, 0.05f));
    prototype.setColorRange(osgParticle::rangev4(osg::Vec4(1, 0.9f, 0.3f, 1), osg::Vec4(1, 0.2f, 0.1f, 0.2f)));

    osg::ref_ptr<osgParticle::ModularEmitter> emitter = new osgParticle::ModularEmitter;
    emitter->setParticleSystem(particles.get());
    osg::ref_ptr<osgParticle::RandomRateCounter> rate = new osgParticle::RandomRateCounter;
    rate->setRateRange(60.0f, 120.0f); // particles per second
    emitter->setCounter(rate.get());
    osg::ref_ptr<osgParticle::SectorPlacer> placer = new osgParticle::SectorPlacer;
    placer->setCenter(osg::Vec3(0, 0, 0.2f));
    placer->setRadiusRange(0.0f, 0.3f);
    emitter->setPlacer(placer.get());
    osg::ref_ptr<osgParticle::RadialShooter> shooter = new osgParticle::RadialShooter;
    shooter->setThetaRange(0.0f, 0.5f); // radians from +Z
    shooter->setInitialSpeedRange(4.0f, 6.0f); // m/s: up to about 1.8 m high under gravity
    emitter->setShooter(shooter.get());

    osg::ref_ptr<osgParticle::ModularProgram> program = new osgParticle::ModularProgram;
    program->setParticleSystem(particles.get());
    osg::ref_ptr<osgParticle::AccelOperator> gravity = new osgParticle::AccelOperator;
    gravity->setToGravity();
    program->addOperator(gravity.get());

    // The particles' state (unlit, blended) on their geode: OSG 3.6's ParticleSystem wrapper does not write the
    // drawable's own state set.
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setStateSet(particles->getStateSet());
    particles->setStateSet(nullptr);
    geode->addDrawable(particles.get());
    osg::ref_ptr<osgParticle::ParticleSystemUpdater> updater = new osgParticle::ParticleSystemUpdater;
    updater->addParticleSystem(particles.get());

    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(floor().get());
    root->addChild(emitter.get());
    root->addChild(program.get());
    root->addChild(geode.get());
    root->addChild(updater.get());
    return root;
}

osg::ref_ptr<osg::Node> twoBoxesScene(const osg::Vec4& rightColour)
{
    osg::ref_ptr<osg::MatrixTransform> left = new osg::MatrixTransform(osg::Matrix::translate(-1.2, 0, 0));
    left->addChild(box(osg::Vec3(), osg::Vec3(0.7f, 0.3f, 0.5f), osg::Vec4(1, 1, 1, 1)).get());
    // 30 degrees every half second, a turn in 6 s: every frame at 2 per second shows the box differently.
    osg::ref_ptr<osg::AnimationPath> turning = new osg::AnimationPath;
    turning->setLoopMode(osg::AnimationPath::LOOP);
    for (int i = 0; i <= 12; ++i)
    {
        const osg::Quat turn(osg::DegreesToRadians(30.0 * i), osg::Vec3d(0, 0, 1));
        turning->insert(0.5 * i, osg::AnimationPath::ControlPoint(osg::Vec3d(-1.2, 0, 0), turn));
    }
    left->setUpdateCallback(new osg::AnimationPathCallback(turning.get()));
    osg::ref_ptr<osg::MatrixTransform> right = new osg::MatrixTransform(osg::Matrix::translate(1.2, 0, 0));
    right->addChild(box(osg::Vec3(), osg::Vec3(0.5f, 0.5f, 0.5f), rightColour).get());
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(left.get());
    root->addChild(right.get());
    return root;
}

bool write(const osg::Node& scene, const std::string& file)
{
    if (osgDB::writeNodeFile(scene, file)) return true;
    std::cerr << "osgactor_make_test_scenes: cannot write " << file << std::endl;
    return false;
}

} // namespace

int main(int argc, char** argv)
{
    if (argc != 2)
    {
        std::cerr << "usage: osgactor_make_test_scenes <folder>" << std::endl;
        return 2;
    }
    const std::string folder = std::string(argv[1]) + "/";
    const bool written = write(*animationPathScene(), folder + "animation_path.osgt") &&
                         write(*osgAnimationScene(), folder + "osganimation.osgt") &&
                         write(*particleScene(), folder + "particles.osgt") &&
                         write(*twoBoxesScene(osg::Vec4(1, 1, 1, 1)), folder + "two_boxes.osgt") &&
                         write(*twoBoxesScene(osg::Vec4(0.9f, 0.1f, 0.1f, 1)), folder + "two_boxes_changed.osgt");
    return written ? 0 : 1;
}
