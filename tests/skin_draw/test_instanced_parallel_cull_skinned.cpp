// The instanced cull of skinned actors on the group's threads (InstancedActorGroup, osgActor/detail/
// InstancedCullParallel.cpp) makes the render graph, the texels (each instance's model-view matrix and palette), the
// near and far planes and the statistics of the cull on one thread, to the bit: two groups of clones of one skinned
// chain (one shared SkinnedMesh), one culled on one thread, one on two, updated alike, compared leaf by leaf and texel
// by texel, moving, partly behind the camera, one actor skinned on the CPU (drawn ordinarily).
#include "InstancedCullComparison"
#include "SkinDrawTestUtil"

#include <osgActor/InstancedActorGroup>

#include <osg/FrameStamp>
#include <osgUtil/UpdateVisitor>

#include <gtest/gtest.h>

#include <cstring>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Leaves of the ordinary traversal alike: the same, or each crowd's actor's own CPU-skinned geometry with the same
  * vertices, at the same place. */
bool sameOrdinaryLeaf(const CulledLeaf& expected, const CulledLeaf& actual)
{
    if (expected == actual) return true;
    const auto* e = dynamic_cast<const osg::Geometry*>(expected.drawable);
    const auto* a = dynamic_cast<const osg::Geometry*>(actual.drawable);
    const auto* ev = e ? dynamic_cast<const osg::Vec3Array*>(e->getVertexArray()) : nullptr;
    const auto* av = a ? dynamic_cast<const osg::Vec3Array*>(a->getVertexArray()) : nullptr;
    return ev && av && ev->size() == av->size() && ev->size() > 0 &&
           std::memcmp(ev->getDataPointer(), av->getDataPointer(), ev->getTotalDataSize()) == 0 &&
           expected.bin == actual.bin && expected.depth == actual.depth &&
           std::memcmp(expected.modelView, actual.modelView, sizeof expected.modelView) == 0;
}

/** 24 clones of a skinned chain in each of two groups, every seventh behind the camera; the parallel group culls on
  * two threads from 4 actors on, the serial one never (both update on two). */
struct TwinSkinnedCrowds
{
    SyntheticActor prototype = makeChainActor(8);
    osg::ref_ptr<InstancedActorGroup> serial = new InstancedActorGroup;
    osg::ref_ptr<InstancedActorGroup> parallel = new InstancedActorGroup;
    std::vector<osg::ref_ptr<ActorNode>> actors[2]; // serial's, parallel's
    CullProbe serialProbe{serial.get()};
    CullProbe parallelProbe{parallel.get()};
    unsigned frame = 0;

    TwinSkinnedCrowds()
    {
        serial->setNumThreads(2);
        parallel->setNumThreads(2);
        serial->setMinActorsForParallelCull(~0u);
        parallel->setMinActorsForParallelCull(4);
        for (unsigned g = 0; g < 2; ++g)
            for (unsigned a = 0; a < 24; ++a)
            {
                osg::ref_ptr<ActorNode> actor = osg::clone(prototype.actor.get(), osg::CopyOp::SHALLOW_COPY);
                const bool behind = a % 7 == 6;
                actor->setPreTranslation(osg::Vec3d(0.25 * (a % 6) - 0.6, behind ? -3.0 : 0.3 * (a / 6), 0.0));
                actors[g].push_back(actor);
                (g ? parallel : serial)->addChild(actor.get());
            }
        for (CullProbe* probe : {&serialProbe, &parallelProbe})
            probe->lookAt(osg::Vec3d(0.0, -1.6, 0.9), osg::Vec3d(0.0, 0.5, 0.0));
    }
    /** Both crowds posed for time t and updated as a viewer updates them. */
    void update(double t)
    {
        ++frame;
        for (unsigned g = 0; g < 2; ++g)
        {
            for (std::size_t a = 0; a < actors[g].size(); ++a) poseSynthetic(*actors[g][a], t + 0.37 * double(a));
            osg::ref_ptr<osg::FrameStamp> stamp = new osg::FrameStamp;
            stamp->setFrameNumber(frame);
            stamp->setSimulationTime(t);
            osg::ref_ptr<osgUtil::UpdateVisitor> visitor = new osgUtil::UpdateVisitor;
            visitor->setFrameStamp(stamp.get());
            visitor->setTraversalNumber(frame);
            (g ? parallel : serial)->accept(*visitor);
        }
    }
    void computeNearFar(osg::CullSettings::ComputeNearFarMode mode)
    {
        serialProbe.sceneView().setComputeNearFarMode(mode);
        parallelProbe.sceneView().setComputeNearFarMode(mode);
    }
    ::testing::AssertionResult cullAlike()
    {
        const unsigned before = parallel->getNumParallelCulls();
        const std::vector<CulledLeaf> expected = withoutOwnStates(serialProbe, serialProbe.cull(frame));
        const std::vector<CulledLeaf> actual = withoutOwnStates(parallelProbe, parallelProbe.cull(frame));
        if (parallel->getNumParallelCulls() != before + 1 || serial->getNumParallelCulls() != 0)
            return ::testing::AssertionFailure() << "not culled on the threads";
        ::testing::AssertionResult same = sameInstancedCull(expected, actual, sameOrdinaryLeaf);
        if (same) same = sameStatistics(*serial, *parallel);
        if (same) same = sameNearFar(serialProbe, parallelProbe);
        return same;
    }
};

} // namespace

TEST(InstancedParallelCullSkinned, AMovingSkinnedCrowdPartlyBehindTheCameraIsTheSerialCull)
{
    for (const osg::CullSettings::ComputeNearFarMode mode :
         {osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR, osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES})
    {
        TwinSkinnedCrowds crowds;
        crowds.computeNearFar(mode);
        for (int at = 0; at < 4; ++at)
        {
            crowds.update(0.2 * at);
            EXPECT_TRUE(crowds.cullAlike()) << "mode " << mode << ", frame " << at;
            // The test can fail: most actors drawn by one instanced draw of the mesh, three behind the camera.
            const InstancedActorGroup::Statistics statistics = crowds.parallel->getStatistics();
            EXPECT_EQ(statistics.actorsOutOfView, 3u);
            EXPECT_EQ(statistics.skinnedDraws, 1u);
            EXPECT_GT(statistics.skinnedInstances, 15u);
        }
        // One actor skinned on the CPU in each crowd: drawn ordinarily, where it comes among the children.
        setSkinningPath(*crowds.actors[0][4], SkinnedMesh::CPU_SKINNING);
        setSkinningPath(*crowds.actors[1][4], SkinnedMesh::CPU_SKINNING);
        for (int at = 4; at < 6; ++at)
        {
            crowds.update(0.2 * at);
            EXPECT_TRUE(crowds.cullAlike()) << "mode " << mode << ", one on the CPU, frame " << at;
            EXPECT_EQ(crowds.parallel->getStatistics().actorsOrdinary, 1u);
        }
    }
}
