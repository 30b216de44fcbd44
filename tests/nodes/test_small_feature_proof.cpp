// The cull of an actor as one, and the instanced cull, skip the small-feature tests below a joint where a bound over
// the joint's whole subtree proves that none of them could cull anything (osgActor/detail/CullArithmetic.h,
// SmallFeatureProof). Near OSG's threshold the proof must refuse, so that the exact tests decide: a camera moving away
// through the threshold gives, at every distance, the render graph of the ordinary traversal.
#include "CullProbe"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/SkeletonNodeAccess.h>

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Whether the proof holds over one rigid joint whose origin is 0.5 from the actor's (a translation by (0, 0, 0.5)),
  * or over a subtree of the shape given. */
bool holdsOverOneJoint(const osg::BoundingSphere& top, const osg::Vec4& actorVector, float pixelSize,
                       double smallestRadius, const detail::SubtreeShape& shape = {true, 0.5})
{
    return detail::SmallFeatureProof::holds(top, shape, actorVector, pixelSize, smallestRadius);
}

/** The subtree shape the node keeps for the proof, after an update and the bound's computation. */
detail::SubtreeShape shapeOf(const SkeletonNode& node) { return detail::SkeletonNodeAccess::subtreeShape(node); }

/** The pixel-size vector's product grows with the actor frame's z: 0.01 at the origin, plus 0.001 per unit of z. */
const osg::Vec4 kActorVector(0.0f, 0.0f, 0.001f, 0.01f);

/** Four test figures in a row, posed apart, culled one way and the other at each distance of a camera backing away. */
struct Crowd
{
    std::vector<osg::ref_ptr<ActorNode>> actors;

    explicit Crowd(osg::Group& parent) : actors(addPosedRow(parent, 4)) {}
    void setCullMode(ActorNode::CullMode mode)
    {
        for (osg::ref_ptr<ActorNode>& actor : actors) actor->setCullMode(mode);
    }
};

/** Camera distances from 5 to 400 units, each a little farther than the last, so that the joints' balls and then
  * the limbs pass OSG's small-feature threshold (two pixels) between two of them. */
std::vector<double> distancesThroughTheThreshold()
{
    std::vector<double> distances;
    for (double d = 5.0; d < 400.0; d *= 1.07) distances.push_back(d);
    return distances;
}

/** Culls the crowd both ways at each distance, compares the render graphs leaf by leaf and returns the numbers of
  * leaves seen. */
std::set<std::size_t> expectTheOrdinaryGraphAtEveryDistance(osg::Group& scene, Crowd& crowd)
{
    CullProbe probe(&scene);
    std::set<std::size_t> counts;
    unsigned frame = 0;
    for (double distance : distancesThroughTheThreshold())
    {
        probe.lookAt(osg::Vec3d(1.6, -distance, 1.0), osg::Vec3d(1.6, 0.0, 0.9));
        crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
        const std::vector<CulledLeaf> ordinary = probe.cull(++frame);
        crowd.setCullMode(ActorNode::CULL_AS_ONE);
        const std::vector<CulledLeaf> asOne = probe.cull(++frame);
        EXPECT_EQ(asOne.size(), ordinary.size()) << "at " << distance;
        for (std::size_t i = 0; i < ordinary.size() && i < asOne.size(); ++i)
            EXPECT_TRUE(asOne[i] == ordinary[i]) << "at " << distance;
        counts.insert(ordinary.size());
    }
    return counts;
}

} // namespace

TEST(SmallFeatureProof, RefusesAJointWithoutABound)
{
    EXPECT_FALSE(holdsOverOneJoint(osg::BoundingSphere(), kActorVector, 2.0f, 1.0));
}

TEST(SmallFeatureProof, RefusesASubtreeWithAMatrixThatIsNotRigid)
{
    const osg::BoundingSphere top(osg::Vec3(), 1.0f);
    // Far above the threshold but for the matrices: a scale moves each frame's pixel-size vector and shrinks spheres.
    EXPECT_TRUE(holdsOverOneJoint(top, kActorVector, 2.0f, 1.0));
    EXPECT_FALSE(holdsOverOneJoint(top, kActorVector, 2.0f, 1.0, {false, 0.5}));
}

TEST(SmallFeatureProof, FindsRotationsAndTranslationsRigidAndScalesShearsProjectionsAndNaNNot)
{
    const osg::Matrixd turned = osg::Matrixd::rotate(0.7, osg::Vec3d(1.0, 2.0, 3.0)) * osg::Matrixd::translate(4.0, -5.0, 6.0);
    EXPECT_TRUE(detail::isRigid(turned.ptr()));
    EXPECT_TRUE(detail::isRigid(osg::Matrixd::identity().ptr()));
    EXPECT_FALSE(detail::isRigid((osg::Matrixd::scale(0.5, 0.5, 0.5) * turned).ptr()));
    EXPECT_FALSE(detail::isRigid((osg::Matrixd::scale(1.0, 1.0, 1.0 + 1e-6) * turned).ptr()));
    osg::Matrixd sheared = turned;
    sheared(1, 0) += 1e-6;
    EXPECT_FALSE(detail::isRigid(sheared.ptr()));
    osg::Matrixd projective;
    projective(0, 3) = 0.1;
    EXPECT_FALSE(detail::isRigid(projective.ptr()));
    osg::Matrixd notANumber = turned;
    notANumber(2, 2) = std::nan("");
    EXPECT_FALSE(detail::isRigid(notANumber.ptr()));
    // The reach: the translation's absolute components, summed.
    EXPECT_DOUBLE_EQ(detail::translationReach(turned.ptr()), 15.0);
}

TEST(SmallFeatureProof, HoldsOnlyWhereTheLargestProductOverTheJointsSphereStaysBelowTheSmallestRadius)
{
    // A unit sphere at the origin: the product reaches 0.01 + 0.001 * 1 = 0.011 at its top, times 2 pixels 0.022.
    const osg::BoundingSphere top(osg::Vec3(), 1.0f);
    EXPECT_TRUE(holdsOverOneJoint(top, kActorVector, 2.0f, 0.0225));
    // At the threshold, and just above it within the margin for rounding: the exact tests must decide.
    EXPECT_FALSE(holdsOverOneJoint(top, kActorVector, 2.0f, 0.022));
    EXPECT_FALSE(holdsOverOneJoint(top, kActorVector, 2.0f, 0.02201));
    // The same sphere raised by 10 units: the product at its top is 0.021, times 2 pixels 0.042.
    const osg::BoundingSphere raised(osg::Vec3(0.0f, 0.0f, 10.0f), 1.0f);
    EXPECT_FALSE(holdsOverOneJoint(raised, kActorVector, 2.0f, 0.0225));
    EXPECT_TRUE(holdsOverOneJoint(raised, kActorVector, 2.0f, 0.045));
    // Without a pixel size to compare with, nothing is proved.
    EXPECT_FALSE(holdsOverOneJoint(top, kActorVector, 0.0f, 1.0));
}

TEST(SmallFeatureProof, WidensItsMarginWithHowFarTheJointsOriginsReach)
{
    // The rounding grows with the coordinates' size in the joints' frames: a joint 10^5 units from the actor's
    // origin (its children's spheres brought back by the geometry) leaves no room at this threshold.
    const osg::BoundingSphere top(osg::Vec3(), 1.0f);
    EXPECT_TRUE(holdsOverOneJoint(top, kActorVector, 2.0f, 0.0225));
    EXPECT_FALSE(holdsOverOneJoint(top, kActorVector, 2.0f, 0.0225, {true, 1e5}));
}

TEST(SmallFeatureProof, ACameraBackingAwayThroughTheThresholdGetsTheOrdinaryRenderGraphAtEveryDistance)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    Crowd crowd(*scene);
    const std::set<std::size_t> counts = expectTheOrdinaryGraphAtEveryDistance(*scene, crowd);
    // The test can fail: near, every part is drawn; far, the balls and then the limbs were dropped, a few at a time.
    EXPECT_EQ(*counts.rbegin(), 4u * 18u);
    EXPECT_GT(counts.size(), 3u);
}

TEST(SmallFeatureProof, AJointScaledByHandIsTestedExactly)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    Crowd crowd(*scene);
    // Halved: its spheres and its parts' are smaller than the rigid figures' and reach the threshold sooner.
    SkeletonNode& knee = *crowd.actors[1]->getSkeletonNode("l_knee");
    knee.setMatrix(osg::Matrixd::scale(0.5, 0.5, 0.5) * knee.getMatrix());
    EXPECT_GT(expectTheOrdinaryGraphAtEveryDistance(*scene, crowd).size(), 3u);
}

TEST(SmallFeatureProof, TheInstancedCullDrawsTheOrdinaryTraversalsPartsAtEveryDistance)
{
    osg::ref_ptr<osg::Group> plain = new osg::Group;
    osg::ref_ptr<InstancedActorGroup> instanced = new InstancedActorGroup;
    Crowd crowd(*plain);
    for (const osg::ref_ptr<ActorNode>& actor : crowd.actors) instanced->addChild(actor.get());
    CullProbe ordinaryProbe(plain.get()), instancedProbe(instanced.get());
    std::set<unsigned> counts;
    unsigned frame = 0;
    for (double distance : distancesThroughTheThreshold())
    {
        ordinaryProbe.lookAt(osg::Vec3d(1.6, -distance, 1.0), osg::Vec3d(1.6, 0.0, 0.9));
        instancedProbe.lookAt(osg::Vec3d(1.6, -distance, 1.0), osg::Vec3d(1.6, 0.0, 0.9));
        crowd.setCullMode(ActorNode::CULL_NODE_BY_NODE);
        const std::vector<CulledLeaf> ordinary = ordinaryProbe.cull(++frame);
        crowd.setCullMode(ActorNode::CULL_AS_ONE);
        instancedProbe.cull(++frame);
        const InstancedActorGroup::Statistics statistics = instanced->getStatistics();
        EXPECT_EQ(statistics.actorsInstanced, 4u);
        // Each instance one drawable the ordinary traversal draws (the images' tests compare what is drawn).
        EXPECT_EQ(statistics.instances, ordinary.size()) << "at " << distance;
        counts.insert(statistics.instances);
    }
    EXPECT_EQ(*counts.rbegin(), 4u * 18u);
    EXPECT_GT(counts.size(), 3u);
}

// The proof reads no joint's matrix at the cull: each skeleton node keeps, with its bound, whether its subtree's
// matrices are rigid. The actor writes rigid matrices; a matrix set by hand through osg::MatrixTransform::setMatrix()
// (not virtual) must still be seen, whatever the state of the bounds when it is set.

namespace {

/** Four posed test figures whose bounds are computed, and what their top joint keeps of its subtree. */
struct BoundedCrowd
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    Crowd crowd{*scene};

    BoundedCrowd()
    {
        for (osg::ref_ptr<ActorNode>& actor : crowd.actors) actor->getBound();
    }
    bool isRigidBelowPelvis(unsigned actor) const { return shapeOf(*crowd.actors[actor]->getSkeletonNode("pelvis")).rigid; }
    /** Scales a joint of an actor by hand, through the base class's setMatrix(), as a user would. */
    osg::MatrixTransform& scaleByHand(unsigned actor, const char* joint, double scale)
    {
        osg::MatrixTransform& node = *crowd.actors[actor]->getSkeletonNode(joint);
        node.setMatrix(osg::Matrixd::scale(scale, scale, scale) * node.getMatrix());
        return node;
    }
    std::size_t countGraphsThroughTheThreshold() { return expectTheOrdinaryGraphAtEveryDistance(*scene, crowd).size(); }
};

} // namespace

TEST(SmallFeatureProof, SeesAMatrixScaledByHandAfterTheBoundsWereComputed)
{
    BoundedCrowd crowd;
    EXPECT_TRUE(crowd.isRigidBelowPelvis(1));
    crowd.scaleByHand(1, "l_knee", 0.5);
    EXPECT_FALSE(crowd.isRigidBelowPelvis(1));
    EXPECT_TRUE(crowd.isRigidBelowPelvis(0));
    EXPECT_GT(crowd.countGraphsThroughTheThreshold(), 3u);
}

TEST(SmallFeatureProof, SeesAMatrixScaledByHandWhileItsBoundWasDirty)
{
    BoundedCrowd crowd;
    // Dirtied first (by a user, or by the actor's write of a joint whose bound follows the pose): setMatrix()'s own
    // dirtying then stops at the knee.
    crowd.crowd.actors[2]->getSkeletonNode("r_knee")->dirtyBound();
    crowd.scaleByHand(2, "r_knee", 2.0);
    EXPECT_FALSE(crowd.isRigidBelowPelvis(2));
    EXPECT_GT(crowd.countGraphsThroughTheThreshold(), 3u);
}

TEST(SmallFeatureProof, TrustsTheSubtreeAgainOnceTheActorHasWrittenItsRigidMatrixBack)
{
    BoundedCrowd crowd;
    const osg::MatrixTransform& knee = crowd.scaleByHand(1, "l_knee", 0.5);
    EXPECT_FALSE(crowd.isRigidBelowPelvis(1));
    // The knee's next pose is written over the scale: the ball made for the scaled matrix is made anew.
    crowd.crowd.actors[1]->setDof("l_knee.rx", 0.3);
    crowd.crowd.actors[1]->update(nullptr);
    EXPECT_TRUE(crowd.isRigidBelowPelvis(1));
    EXPECT_TRUE(detail::isRigid(knee.getMatrix().ptr()));
    EXPECT_GT(crowd.countGraphsThroughTheThreshold(), 3u);
}

TEST(SmallFeatureProof, KnowsNothingOfASubtreeWhoseBoundACallbackComputes)
{
    BoundedCrowd crowd;
    // A callback computes the knee's bound in place of computeBound(), which notes the subtree's shape: the
    // callback set without dirtying anything, then a scale.
    struct KneeBound : osg::Node::ComputeBoundingSphereCallback
    {
        osg::BoundingSphere computeBound(const osg::Node&) const override
        {
            return osg::BoundingSphere(osg::Vec3(0.0f, 0.0f, -0.25f), 0.3f);
        }
    };
    crowd.crowd.actors[3]->getSkeletonNode("r_knee")->setComputeBoundingSphereCallback(new KneeBound);
    EXPECT_TRUE(crowd.isRigidBelowPelvis(3)); // nothing changed yet
    crowd.scaleByHand(3, "r_knee", 0.5);
    EXPECT_FALSE(crowd.isRigidBelowPelvis(3));
    EXPECT_GT(crowd.countGraphsThroughTheThreshold(), 3u);
}

TEST(SmallFeatureProof, KeepsTheSubtreesReachFromTheActorsOrigin)
{
    BoundedCrowd crowd;
    ActorNode& actor = *crowd.crowd.actors[0];
    // pelvis 0.95 up; chest 0.45 above it, head above the chest; a hip 0.1 aside and its knee 0.45 below: the
    // farthest sum of translations on the way down is the longest of those chains.
    const detail::SubtreeShape pelvis = shapeOf(*actor.getSkeletonNode("pelvis"));
    const detail::SubtreeShape chest = shapeOf(*actor.getSkeletonNode("chest"));
    EXPECT_TRUE(pelvis.rigid);
    EXPECT_GE(pelvis.reach, 0.95 + 0.45);
    EXPECT_NEAR(pelvis.reach, 0.95 + chest.reach, 1e-12);
    // Moved by hand far from the actor: the reach grows with it.
    SkeletonNode& head = *actor.getSkeletonNode("head");
    head.setMatrix(osg::Matrixd::translate(0.0, 0.0, 1e5));
    EXPECT_NEAR(shapeOf(*actor.getSkeletonNode("pelvis")).reach, 0.95 + 0.45 + 1e5, 1e-6);
}
