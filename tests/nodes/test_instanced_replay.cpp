// The instanced cull (InstancedActorGroup, osgActor/detail/InstancedCull.h) keeps the instances of an actor that did
// not change and adds them again while nothing they depend on changes (its pose, plan and bound, the camera and the
// cull's settings), as the cull as one replays its calls. Each instance must stay the ordinary traversal's drawable at
// its model-view matrix rounded to floats: frame after frame of a still crowd, and after the camera or a pose moves.
#include "CullProbe"
#include "InstancedCullComparison"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/InstancedDraw.h>

#include <osg/TextureBuffer>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <iomanip>
#include <set>
#include <utility>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Four test figures, posed apart, under an instanced group and, the same nodes, under a plain group culled node by
  * node; near and far not computed (with them, nothing is kept). */
struct Scene
{
    osg::ref_ptr<InstancedActorGroup> instanced = new InstancedActorGroup;
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    std::vector<osg::ref_ptr<ActorNode>> actors;
    CullProbe instancedProbe{instanced.get()};
    CullProbe ordinaryProbe{plain.get()};
    unsigned frame = 0;

    /** clones: the four are clones of one figure (they share its parts, so their instances share batches). */
    explicit Scene(bool clones = false)
    {
        actors = addPosedRow(*plain, 4);
        if (clones)
        {
            osg::ref_ptr<ActorNode> figure = makeTestFigure();
            for (unsigned a = 0; a < actors.size(); ++a)
            {
                osg::ref_ptr<ActorNode> clone = osg::clone(figure.get(), osg::CopyOp::SHALLOW_COPY);
                clone->setPreTranslation(actors[a]->getPreTranslation());
                poseCrowdMember(*clone, a);
                clone->update(nullptr);
                plain->setChild(a, clone.get());
                actors[a] = clone;
            }
        }
        for (const osg::ref_ptr<ActorNode>& actor : actors) instanced->addChild(actor.get());
        for (CullProbe* probe : {&instancedProbe, &ordinaryProbe})
            probe->sceneView().setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        lookFrom(osg::Vec3d(1.6, -7.0, 1.2));
    }
    void lookFrom(const osg::Vec3d& eye, const osg::Vec3d& center = osg::Vec3d(1.6, 0.0, 0.9))
    {
        instancedProbe.lookAt(eye, center);
        ordinaryProbe.lookAt(eye, center);
    }
    /** Near and far computed from bounding volumes (SceneView's default, osgViewer's) by both cull visitors. */
    void computeNearFarFromBounds() { computeNearFar(osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES); }
    void computeNearFar(osg::CullSettings::ComputeNearFarMode mode)
    {
        for (CullProbe* probe : {&instancedProbe, &ordinaryProbe}) probe->sceneView().setComputeNearFarMode(mode);
    }
    std::vector<Instance> cullInstanced() { return instancesOf(instancedProbe.cull(++frame)); }
    /** The ordinary traversal's instances, and its computed near and far (ordinaryNear, ordinaryFar). */
    std::vector<Instance> cullOrdinarily()
    {
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(ActorNode::CULL_NODE_BY_NODE);
        std::vector<Instance> instances = ordinaryInstancesOf(ordinaryProbe.cull(++frame));
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(ActorNode::CULL_AS_ONE);
        ordinaryNear = ordinaryProbe.calculatedNear();
        ordinaryFar = ordinaryProbe.calculatedFar();
        return instances;
    }
    /** Whether the instanced cull's computed near and far are the ordinary traversal's last ones, to the bit. */
    ::testing::AssertionResult sameNearFarAsOrdinary() const
    {
        const double nearPlane = instancedProbe.calculatedNear(), farPlane = instancedProbe.calculatedFar();
        if (std::memcmp(&nearPlane, &ordinaryNear, sizeof(double)) == 0 &&
            std::memcmp(&farPlane, &ordinaryFar, sizeof(double)) == 0)
            return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << std::setprecision(17) << "near " << nearPlane << ", far " << farPlane
                                             << " against the ordinary " << ordinaryNear << ", " << ordinaryFar;
    }
    double ordinaryNear = 0.0;
    double ordinaryFar = 0.0;
};

} // namespace

TEST(InstancedReplay, AStillCrowdBeforeAStillCameraGivesTheOrdinaryInstancesFrameAfterFrame)
{
    Scene scene;
    const std::vector<Instance> ordinary = scene.cullOrdinarily();
    ASSERT_EQ(ordinary.size(), 4u * 18u); // the test can fail: every part is seen
    // The first frames cull afresh, the next ones add what was kept.
    for (int frame = 0; frame < 5; ++frame)
    {
        EXPECT_EQ(scene.cullInstanced(), ordinary) << "frame " << frame;
        EXPECT_EQ(scene.instanced->getStatistics().actorsInstanced, 4u);
    }
}

TEST(InstancedReplay, AMovedCameraOrAPoseChangeIsCulledAfresh)
{
    Scene scene;
    for (int frame = 0; frame < 3; ++frame) scene.cullInstanced();
    scene.lookFrom(osg::Vec3d(0.5, -6.0, 2.0));
    const std::vector<Instance> moved = scene.cullOrdinarily();
    EXPECT_EQ(scene.cullInstanced(), moved);
    EXPECT_EQ(scene.cullInstanced(), moved);
    // A pose changed by hand, without a controller: the next update writes it to the joints.
    scene.actors[2]->setDof("l_shoulder.ry", -1.5);
    scene.actors[2]->update(nullptr);
    const std::vector<Instance> posed = scene.cullOrdinarily();
    EXPECT_NE(posed, moved); // the test can fail: the arm's parts moved
    EXPECT_EQ(scene.cullInstanced(), posed);
    EXPECT_EQ(scene.cullInstanced(), posed);
    // A joint matrix set by hand: the bound below it is recomputed.
    SkeletonNode& knee = *scene.actors[1]->getSkeletonNode("r_knee");
    knee.setMatrix(osg::Matrixd::rotate(0.4, osg::X_AXIS) * knee.getMatrix());
    const std::vector<Instance> bent = scene.cullOrdinarily();
    EXPECT_NE(bent, posed);
    EXPECT_EQ(scene.cullInstanced(), bent);
    EXPECT_EQ(scene.cullInstanced(), bent);
}

TEST(InstancedReplay, ACrowdMovingEveryFrameGivesTheOrdinaryInstancesWhateverTheCullMustTest)
{
    // Every actor posed anew at every frame, so none is kept: from the second frame on each batch has room for its
    // instances, and the cull adds a plain plan's instances straight from its compiled list where it need test
    // nothing below the actor; a joint masked out, a scale set by hand (no proof of no small feature) and a far
    // camera (small features culled) make it follow the plan's steps. Each frame: the ordinary traversal's parts.
    Scene scene;
    auto move = [&](int frame) {
        for (std::size_t a = 0; a < scene.actors.size(); ++a)
        {
            scene.actors[a]->setDof("l_shoulder.ry", -0.25 * double(a) - 0.1 * frame);
            scene.actors[a]->setDof("pelvis.rz", 0.05 * frame);
            scene.actors[a]->update(nullptr);
        }
    };
    auto expectOrdinary = [&](int frame, const char* what) {
        move(frame);
        const std::vector<Instance> ordinary = scene.cullOrdinarily();
        EXPECT_EQ(scene.cullInstanced(), ordinary) << what << ", frame " << frame;
        EXPECT_EQ(scene.instanced->getStatistics().actorsInstanced, 4u) << what << ", frame " << frame;
        return ordinary.size();
    };
    int frame = 0;
    for (; frame < 4; ++frame) EXPECT_EQ(expectOrdinary(frame, "moving"), 4u * 18u); // every part seen
    // Each cull culls afresh (instances are kept only for an actor that did not change): the ordinary traversal's
    // count of parts, with the instanced cull's compiled list and its steps alike.
    SkeletonNode& elbow = *scene.actors[3]->getSkeletonNode("l_elbow");
    elbow.setNodeMask(0);
    for (int end = frame + 2; frame < end; ++frame) EXPECT_LT(expectOrdinary(frame, "a joint masked out"), 4u * 18u);
    elbow.setNodeMask(~0u);
    for (int end = frame + 2; frame < end; ++frame) expectOrdinary(frame, "unmasked");
    SkeletonNode& knee = *scene.actors[1]->getSkeletonNode("r_knee");
    knee.setMatrix(osg::Matrixd::scale(1.5, 1.5, 1.5) * knee.getMatrix());
    {
        // Not moved this frame (an update would write the knee's matrix again): the scaled knee is culled.
        const std::vector<Instance> ordinary = scene.cullOrdinarily();
        EXPECT_EQ(scene.cullInstanced(), ordinary) << "a joint scaled by hand";
    }
    // A camera backing away through the small-feature threshold, the crowd moving: where the proof holds below a
    // top joint nothing is tested, elsewhere each sphere is, as the ordinary traversal tests it.
    std::set<std::size_t> counts;
    for (double distance = 5.0; distance < 400.0; distance *= 1.07)
    {
        scene.lookFrom(osg::Vec3d(1.6, -distance, 1.2));
        counts.insert(expectOrdinary(frame++, "backing away"));
    }
    EXPECT_EQ(*counts.rbegin(), 4u * 18u);
    EXPECT_GT(counts.size(), 3u); // the test can fail: parts were culled as small features on the way
    scene.lookFrom(osg::Vec3d(1.6, -7.0, 1.2));
    for (int end = frame + 2; frame < end; ++frame) expectOrdinary(frame, "near again");
}

TEST(InstancedReplay, ACrowdOverSeveralSmallBuffersGivesTheOrdinaryInstancesStillMovingAndShrinking)
{
    // Buffers of 7 instances: the frame's instances are drawn from windows of the buffer the cull wrote, a batch's
    // instances in runs. Still actors keep their instances where the last cull added them (written once); a pose
    // changed, or actors masked out and back (the batches' regions move), write them again where they now go.
    Scene scene(true);
    scene.instanced->setMaxTexelsPerBuffer(4 * 7);
    const std::vector<Instance> ordinary = scene.cullOrdinarily();
    ASSERT_EQ(ordinary.size(), 4u * 18u);
    for (int frame = 0; frame < 4; ++frame)
    {
        EXPECT_EQ(scene.cullInstanced(), ordinary) << "still, frame " << frame;
        EXPECT_EQ(scene.instanced->getStatistics().texelLimit, 4u * 7u);
        EXPECT_GE(scene.instanced->getStatistics().buffers, (4u * 18u + 6u) / 7u);
    }
    scene.actors[2]->setDof("l_shoulder.ry", -1.5);
    scene.actors[2]->update(nullptr);
    const std::vector<Instance> posed = scene.cullOrdinarily();
    ASSERT_NE(posed, ordinary);
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(scene.cullInstanced(), posed) << "posed, frame " << frame;
    scene.actors[1]->setNodeMask(0u);
    const std::vector<Instance> three = scene.cullOrdinarily();
    ASSERT_EQ(three.size(), 3u * 18u);
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(scene.cullInstanced(), three) << "three, frame " << frame;
    scene.actors[1]->setNodeMask(~0u);
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(scene.cullInstanced(), posed) << "four again, frame " << frame;
    // The first actor away for one frame: the second's instances are written at its texels meanwhile, so where it
    // comes back to them, its own are written again.
    scene.actors[0]->setNodeMask(0u);
    const std::vector<Instance> away = scene.cullOrdinarily();
    scene.actors[0]->setNodeMask(~0u);
    for (int frame = 0; frame < 3; ++frame) scene.cullInstanced(); // kept where they were added
    scene.actors[0]->setNodeMask(0u);
    EXPECT_EQ(scene.cullInstanced(), away);
    scene.actors[0]->setNodeMask(~0u);
    for (int frame = 0; frame < 3; ++frame) EXPECT_EQ(scene.cullInstanced(), posed) << "back, frame " << frame;
    // Without the cap, one buffer: the instances the same.
    scene.instanced->setMaxTexelsPerBuffer(0);
    for (int frame = 0; frame < 2; ++frame) EXPECT_EQ(scene.cullInstanced(), posed) << "one buffer, frame " << frame;
    EXPECT_EQ(scene.instanced->getStatistics().buffers, 1u);
}

TEST(InstancedReplay, AStillCrowdWithNearAndFarFromBoundsKeepsItsInstancesAndGivesTheOrdinaryNearAndFar)
{
    // osgViewer's default camera: near and far computed from bounding volumes. The kept instances hold there, their
    // near and far merged into the visitor's again: the ordinary traversal's instances and near and far, to the bit.
    Scene scene;
    scene.computeNearFarFromBounds();
    const std::vector<Instance> ordinary = scene.cullOrdinarily();
    ASSERT_EQ(ordinary.size(), 4u * 18u);
    ASSERT_LT(scene.ordinaryNear, scene.ordinaryFar); // the test can fail: near and far were computed
    for (int frame = 0; frame < 6; ++frame)
    {
        EXPECT_EQ(scene.cullInstanced(), ordinary) << "frame " << frame;
        EXPECT_TRUE(scene.sameNearFarAsOrdinary()) << "frame " << frame;
        EXPECT_EQ(scene.instanced->getStatistics().actorsInstanced, 4u);
        // The first cull culls afresh, the second keeps what it culls, the others add it again.
        if (frame >= 2)
        {
            EXPECT_EQ(scene.instanced->getStatistics().actorsKept, 4u) << "frame " << frame;
        }
    }
}

TEST(InstancedReplay, AStillCrowdBeforeACameraWalkingThroughItGivesTheOrdinaryNearAndFarKeptOrNot)
{
    // The eye walks through the second figure, looking along the row's depth: parts in front, parts behind the eye
    // (dropped), parts across its plane (a near distance below zero). At each stop the instanced group culls three
    // times: afresh, kept, added again; each time the ordinary traversal's instances and near and far, to the bit.
    Scene scene;
    scene.computeNearFarFromBounds();
    bool acrossEyePlane = false;
    std::set<std::size_t> counts;
    unsigned keptSeen = 0;
    for (double y = -3.0; y < 1.5; y += 0.15)
    {
        const osg::Vec3d eye(1.1, y, 1.1);
        scene.lookFrom(eye, eye + osg::Vec3d(0.2, 7.0, -0.3));
        const std::vector<Instance> ordinary = scene.cullOrdinarily();
        counts.insert(ordinary.size());
        acrossEyePlane = acrossEyePlane || scene.ordinaryNear < 0.0;
        for (int again = 0; again < 3; ++again)
        {
            EXPECT_EQ(scene.cullInstanced(), ordinary) << "eye at y " << y << ", cull " << again;
            EXPECT_TRUE(scene.sameNearFarAsOrdinary()) << "eye at y " << y << ", cull " << again;
        }
        const InstancedActorGroup::Statistics statistics = scene.instanced->getStatistics();
        EXPECT_EQ(statistics.actorsKept, statistics.actorsInstanced) << "eye at y " << y;
        keptSeen += statistics.actorsKept;
    }
    EXPECT_TRUE(acrossEyePlane); // the test can fail: a part crossed the eye plane on the way
    EXPECT_GT(counts.size(), 3u); // parts were behind the eye or out of view on the way
    EXPECT_GT(keptSeen, 0u);
}

TEST(InstancedReplay, ACrowdMovingEveryFrameWithNearAndFarFromBoundsGivesTheOrdinaryNearAndFar)
{
    // Every actor posed anew at every frame (nothing kept), the camera walking through the row: each drawable's
    // near and far gathered per actor and merged once, the ordinary traversal's values to the bit.
    Scene scene;
    scene.computeNearFarFromBounds();
    bool acrossEyePlane = false;
    int frame = 0;
    for (double y = -7.0; y < 1.5; y += 0.25, ++frame)
    {
        for (std::size_t a = 0; a < scene.actors.size(); ++a)
        {
            scene.actors[a]->setDof("l_shoulder.ry", -0.25 * double(a) - 0.1 * frame);
            scene.actors[a]->setDof("pelvis.rz", 0.05 * frame);
            scene.actors[a]->update(nullptr);
        }
        const osg::Vec3d eye(1.1, y, 1.1);
        scene.lookFrom(eye, eye + osg::Vec3d(0.2, 7.0, -0.3));
        const std::vector<Instance> ordinary = scene.cullOrdinarily();
        acrossEyePlane = acrossEyePlane || scene.ordinaryNear < 0.0;
        EXPECT_EQ(scene.cullInstanced(), ordinary) << "frame " << frame;
        EXPECT_TRUE(scene.sameNearFarAsOrdinary()) << "frame " << frame;
        EXPECT_EQ(scene.instanced->getStatistics().actorsKept, 0u) << "frame " << frame;
    }
    EXPECT_TRUE(acrossEyePlane); // the test can fail: a part crossed the eye plane on the way
}

TEST(InstancedReplay, NearAndFarFromPrimitivesAreTheOrdinaryTraversalsToTheBit)
{
    // From primitives the visitor clips each drawable's triangles against the frustum's planes in the drawable's own
    // frame, the joint's: a crowd moving every frame, the camera walking through the row, each of the two modes.
    for (const osg::CullSettings::ComputeNearFarMode mode :
         {osg::CullSettings::COMPUTE_NEAR_FAR_USING_PRIMITIVES, osg::CullSettings::COMPUTE_NEAR_USING_PRIMITIVES})
    {
        Scene scene;
        scene.computeNearFar(mode);
        int frame = 0;
        for (double y = -7.0; y < 1.5; y += 0.5, ++frame)
        {
            for (std::size_t a = 0; a < scene.actors.size(); ++a)
            {
                scene.actors[a]->setDof("l_shoulder.ry", -0.25 * double(a) - 0.1 * frame);
                scene.actors[a]->update(nullptr);
            }
            const osg::Vec3d eye(1.1, y, 1.1);
            scene.lookFrom(eye, eye + osg::Vec3d(0.2, 7.0, -0.3));
            scene.cullOrdinarily();
            scene.cullInstanced();
            EXPECT_TRUE(scene.sameNearFarAsOrdinary()) << "mode " << mode << ", frame " << frame;
        }
    }
}
