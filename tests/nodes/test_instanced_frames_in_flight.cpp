// The instanced cull with osgViewer's draw thread (DrawThreadPerContext): the render graph of the last frame is still
// held (drawn) while the next one is culled, so the InstancedActorGroup's frames (osgActor/detail/InstancedCull.h)
// alternate, two or more of them. A still crowd before a still camera must write and upload nothing once each frame
// has been filled, in the serial cull and on the group's threads; what changes (an actor moving, the camera, the
// crowd) must be written where it must, and every frame must draw what a fresh cull draws, texel for texel. Each
// frame in flight is a scene view of its own holding its render graph until its next cull, as osgViewer's renderer
// holds one per frame in flight.
#include "CullProbe"
#include "InstancedCullComparison"
#include "render/TestFigure.h"

#include <osgActor/ActorNode>
#include <osgActor/InstancedActorGroup>
#include <osgActor/detail/InstancedDraw.h>

#include <osg/TextureBuffer>

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The image of the texture buffer an instanced leaf reads, or null for another leaf. */
osg::Image* bufferImageOf(const CulledLeaf& leaf)
{
    if (!dynamic_cast<const detail::InstancedDraw*>(leaf.drawable) || leaf.states.empty()) return nullptr;
    const auto* buffer = dynamic_cast<const osg::TextureBuffer*>(leaf.states.back()->getTextureAttribute(
        InstancedActorGroup::kInstanceTextureUnit, osg::StateAttribute::TEXTURE));
    return buffer ? const_cast<osg::Image*>(buffer->getImage()) : nullptr;
}

/** The buffer images a cull's leaves read (one per frame here: no limit splits it). */
std::set<osg::Image*> bufferImagesOf(const std::vector<CulledLeaf>& leaves)
{
    std::set<osg::Image*> images;
    for (const CulledLeaf& leaf : leaves)
        if (osg::Image* image = bufferImageOf(leaf)) images.insert(image);
    return images;
}

/** A float no cull writes: a NaN of a pattern of its own. */
const std::uint32_t kPoison = 0x7fbadbadu;

bool isPoison(const float* value) { return std::memcmp(value, &kPoison, sizeof kPoison) == 0; }

/** A crowd under an InstancedActorGroup culled by framesInFlight scene views in turn (the render graph of each held
  * until its next cull: the group's frames alternate), and a twin crowd (clones of the same figure, so the same parts,
  * placed and posed alike) that a new group culls afresh, for reference. */
struct FramesInFlight
{
    osg::ref_ptr<ActorNode> figure = makeTestFigure();
    osg::ref_ptr<InstancedActorGroup> group = new InstancedActorGroup;
    std::vector<osg::ref_ptr<ActorNode>> actors;
    std::vector<osg::ref_ptr<ActorNode>> twins;
    std::vector<std::unique_ptr<CullProbe>> probes;
    std::vector<std::vector<CulledLeaf>> held; // per probe, its last cull's leaves
    osg::Vec3d eye{1.5, -2.5, 1.6};
    osg::Vec3d centre{2.0, 3.0, 0.9};
    unsigned frame = 0;
    bool inParallel;

    FramesInFlight(unsigned framesInFlight, unsigned numActors, bool parallel) : inParallel(parallel)
    {
        group->setNumThreads(parallel ? 2 : 1);
        group->setMinActorsForParallelCull(4);
        for (unsigned a = 0; a < numActors; ++a)
        {
            actors.push_back(placed(a));
            twins.push_back(placed(a));
            group->addChild(actors.back().get());
        }
        for (unsigned k = 0; k < framesInFlight; ++k)
        {
            probes.emplace_back(new CullProbe(group.get()));
            setUp(*probes.back());
        }
        held.resize(framesInFlight);
    }
    osg::ref_ptr<ActorNode> placed(unsigned a) const
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(figure.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(1.1 * (a % 6), 1.5 * (a / 6), 0.0));
        poseCrowdMember(*actor, a % 7);
        actor->update(nullptr);
        return actor;
    }
    void setUp(CullProbe& probe) const
    {
        probe.sceneView().setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        probe.lookAt(eye, centre);
    }
    void lookFrom(const osg::Vec3d& newEye)
    {
        eye = newEye;
        for (std::unique_ptr<CullProbe>& probe : probes) probe->lookAt(eye, centre);
    }
    /** Actor a posed at the frame, and its twin. */
    void move(unsigned a, int at)
    {
        for (ActorNode* actor : {actors[a].get(), twins[a].get()})
        {
            actor->setDof("l_shoulder.ry", -0.3 - 0.1 * at);
            actor->update(nullptr);
        }
    }
    /** The scene view whose frame the next cull takes the place of, and its last leaves. */
    unsigned nextProbe() const { return frame % unsigned(probes.size()); }
    /** The next frame's cull by the next scene view, the others' render graphs held. */
    std::vector<CulledLeaf> cull()
    {
        const unsigned k = nextProbe();
        const unsigned parallelBefore = group->getNumParallelCulls();
        held[k] = withoutOwnStates(*probes[k], probes[k]->cull(++frame));
        EXPECT_EQ(group->getNumParallelCulls() - parallelBefore, inParallel ? 1u : 0u) << "frame " << frame;
        return held[k];
    }
    /** The twin crowd culled afresh by a group of its own (kept, with its scene view, until the next such cull: the
      * leaves name its draws and buffers). */
    std::vector<CulledLeaf> cullAfresh()
    {
        freshGroup = new InstancedActorGroup;
        freshGroup->setNumThreads(1);
        for (const osg::ref_ptr<ActorNode>& twin : twins) freshGroup->addChild(twin.get());
        freshProbe.reset(new CullProbe(freshGroup.get()));
        setUp(*freshProbe);
        return withoutOwnStates(*freshProbe, freshProbe->cull(frame));
    }
    osg::ref_ptr<InstancedActorGroup> freshGroup;
    std::unique_ptr<CullProbe> freshProbe;
    /** How many times the buffers the frames' leaves read were marked for upload so far. */
    unsigned uploads() const
    {
        std::set<osg::Image*> images;
        for (const std::vector<CulledLeaf>& leaves : held)
            for (osg::Image* image : bufferImagesOf(leaves)) images.insert(image);
        unsigned count = 0;
        for (const osg::Image* image : images) count += image->getModifiedCount();
        return count;
    }
    /** Whether the frames alternate: each scene view's leaves read a buffer of their own. */
    bool framesAlternate() const
    {
        std::set<osg::Image*> images;
        for (const std::vector<CulledLeaf>& leaves : held)
        {
            const std::set<osg::Image*> own = bufferImagesOf(leaves);
            if (own.size() != 1) return false;
            images.insert(*own.begin());
        }
        return images.size() == held.size();
    }
};

/** Culls as fc.cull() does, and counts the instances it wrote into the frame it took: the frame's buffer (that of the
  * cull framesInFlight culls before, which the next cull takes again) filled with poison first, what was not written
  * given its texels back after. Returns the leaves. */
std::vector<CulledLeaf> cullCountingWrites(FramesInFlight& fc, unsigned& written)
{
    const std::set<osg::Image*> images = bufferImagesOf(fc.held[fc.nextProbe()]);
    EXPECT_EQ(images.size(), 1u);
    osg::Image& image = **images.begin();
    float* texels = reinterpret_cast<float*>(image.data());
    const std::size_t floats = image.getTotalSizeInBytes() / sizeof(float);
    const std::vector<float> before(texels, texels + floats);
    for (std::size_t k = 0; k < floats; ++k) std::memcpy(&texels[k], &kPoison, sizeof kPoison);
    std::vector<CulledLeaf> leaves = fc.cull();
    written = 0;
    EXPECT_EQ(bufferImagesOf(leaves), images); // the same frame, its buffer not made anew
    if (reinterpret_cast<float*>(image.data()) != texels) return leaves;
    for (const CulledLeaf& leaf : leaves)
    {
        const auto* draw = dynamic_cast<const detail::InstancedDraw*>(leaf.drawable);
        if (!draw) continue;
        for (unsigned i = 0; i < draw->getNumInstances(); ++i)
            if (!isPoison(texels + 4 * (std::size_t(draw->getBase()) + std::size_t(draw->getTexelsPerInstance()) * i)))
                ++written;
    }
    for (std::size_t k = 0; k < floats; ++k)
        if (isPoison(&texels[k])) texels[k] = before[k];
    return leaves;
}

/** Whether two culls draw the same: the same leaves in the same order, each instanced draw of the same geometry and
  * instances, the texels it reads the same, bit for bit, wherever they lie in its buffer (a cull after a change may
  * lay its batches out otherwise than a fresh cull does). */
::testing::AssertionResult drawsTheSame(const std::vector<CulledLeaf>& expected, const std::vector<CulledLeaf>& actual)
{
    if (expected.size() != actual.size())
        return ::testing::AssertionFailure() << actual.size() << " leaves, not " << expected.size();
    unsigned instances = 0;
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
        const auto* e = dynamic_cast<const detail::InstancedDraw*>(expected[i].drawable);
        const auto* a = dynamic_cast<const detail::InstancedDraw*>(actual[i].drawable);
        if (!e || !a) return ::testing::AssertionFailure() << "leaf " << i << " is not an instanced draw";
        if (e->getGeometry() != a->getGeometry() || e->getNumInstances() != a->getNumInstances() ||
            e->getTexelsPerInstance() != a->getTexelsPerInstance())
            return ::testing::AssertionFailure() << "leaf " << i << ": " << a->getNumInstances() << " instances, not "
                                                 << e->getNumInstances();
        const std::vector<float> texelsE = texelsDrawnBy(expected[i]), texelsA = texelsDrawnBy(actual[i]);
        if (texelsE.size() != texelsA.size() ||
            std::memcmp(texelsE.data(), texelsA.data(), texelsE.size() * sizeof(float)) != 0)
            return ::testing::AssertionFailure() << "leaf " << i << " reads other texels";
        instances += e->getNumInstances();
    }
    if (instances == 0) return ::testing::AssertionFailure() << "no instance drawn"; // the test can fail
    return ::testing::AssertionSuccess();
}

std::string nameOf(unsigned framesInFlight, bool parallel)
{
    return std::to_string(framesInFlight) + " frames in flight, " + (parallel ? "on the threads" : "serial");
}

} // namespace

TEST(InstancedFramesInFlight, AStillCrowdWritesAndUploadsNothingOnceEachFrameIsFilled)
{
    for (const unsigned framesInFlight : {2u, 3u})
        for (const bool parallel : {false, true})
        {
            const std::string name = nameOf(framesInFlight, parallel);
            FramesInFlight fc(framesInFlight, 24, parallel);
            // The first culls cull afresh and keep; then each frame is filled once with what was kept.
            for (unsigned k = 0; k < 2 * framesInFlight; ++k) fc.cull();
            ASSERT_TRUE(fc.framesAlternate()) << name; // the test can fail: one buffer per frame in flight
            const std::vector<CulledLeaf> fresh = fc.cullAfresh();
            const unsigned uploads = fc.uploads();
            for (unsigned k = 0; k < 2 * framesInFlight; ++k)
            {
                unsigned written = 0;
                const std::vector<CulledLeaf> leaves = cullCountingWrites(fc, written);
                EXPECT_EQ(written, 0u) << name << ", still, cull " << k;
                EXPECT_TRUE(sameInstancedCull(fresh, leaves)) << name << ", still, cull " << k;
                const InstancedActorGroup::Statistics statistics = fc.group->getStatistics();
                EXPECT_GT(statistics.actorsKept, 10u) << name; // the test can fail: actors in view keep theirs
                EXPECT_EQ(statistics.actorsKept, statistics.actorsInstanced) << name;
            }
            EXPECT_EQ(fc.uploads(), uploads) << name << ": a still crowd's frames marked for upload again";
            EXPECT_TRUE(fc.framesAlternate()) << name;
        }
}

TEST(InstancedFramesInFlight, OneActorMovingWritesItselfAloneAndEveryFrameDrawsTheFreshCull)
{
    for (const unsigned framesInFlight : {2u, 3u})
        for (const bool parallel : {false, true})
        {
            const std::string name = nameOf(framesInFlight, parallel);
            FramesInFlight fc(framesInFlight, 24, parallel);
            for (unsigned k = 0; k < 2 * framesInFlight; ++k) fc.cull();
            const unsigned moving = 7;
            unsigned parts = 0;
            for (unsigned k = 0; k < 3 * framesInFlight; ++k)
            {
                fc.move(moving, int(k));
                const std::vector<CulledLeaf> fresh = fc.cullAfresh();
                const unsigned uploads = fc.uploads();
                unsigned written = 0;
                const std::vector<CulledLeaf> leaves = cullCountingWrites(fc, written);
                EXPECT_TRUE(sameInstancedCull(fresh, leaves)) << name << ", moving, cull " << k;
                // The moving actor's parts, culled anew at every cull, and nothing else: the others' instances stay
                // where every frame holds them.
                if (k == 0) parts = written;
                EXPECT_EQ(written, parts) << name << ", moving, cull " << k;
                EXPECT_EQ(fc.uploads(), uploads + 1) << name << ", moving, cull " << k; // its frame alone
            }
            EXPECT_GT(parts, 10u) << name; // the test can fail: the moving actor is in view, all its parts
            EXPECT_LT(parts, 20u) << name;
            // Still again: kept at the next cull, then each frame filled once, then nothing written.
            for (unsigned k = 0; k < framesInFlight + 1; ++k) fc.cull();
            const std::vector<CulledLeaf> fresh = fc.cullAfresh();
            for (unsigned k = 0; k < 2 * framesInFlight; ++k)
            {
                unsigned written = 0;
                EXPECT_TRUE(sameInstancedCull(fresh, cullCountingWrites(fc, written))) << name << ", still again";
                EXPECT_EQ(written, 0u) << name << ", still again, cull " << k;
            }
        }
}

TEST(InstancedFramesInFlight, EveryFrameDrawsTheFreshCullWhenTheCameraOrTheCrowdChanges)
{
    // What moves the instances in the frames (the view, the batches' regions as actors come and go or the crowd
    // grows) is written again in each frame where it must be: each cull draws what a fresh cull draws, texel for
    // texel.
    for (const unsigned framesInFlight : {2u, 3u})
        for (const bool parallel : {false, true})
        {
            const std::string name = nameOf(framesInFlight, parallel);
            FramesInFlight fc(framesInFlight, 24, parallel);
            auto expectFresh = [&](const char* what, unsigned culls) {
                for (unsigned k = 0; k < culls; ++k)
                {
                    const std::vector<CulledLeaf> leaves = fc.cull();
                    EXPECT_TRUE(drawsTheSame(fc.cullAfresh(), leaves)) << name << ", " << what << ", cull " << k;
                }
            };
            expectFresh("still", 3 * framesInFlight);
            fc.lookFrom(osg::Vec3d(1.0, -6.0, 2.0));
            expectFresh("camera moved", 3 * framesInFlight);
            // One actor away for one cull (the next actors' instances take its texels in that frame), then back.
            for (ActorNode* actor : {fc.actors[2].get(), fc.twins[2].get()}) actor->setNodeMask(0u);
            expectFresh("one away", 1);
            for (ActorNode* actor : {fc.actors[2].get(), fc.twins[2].get()}) actor->setNodeMask(~0u);
            expectFresh("back", 3 * framesInFlight);
            // Away for as many culls as there are frames, then back.
            for (ActorNode* actor : {fc.actors[5].get(), fc.twins[5].get()}) actor->setNodeMask(0u);
            expectFresh("away longer", framesInFlight);
            for (ActorNode* actor : {fc.actors[5].get(), fc.twins[5].get()}) actor->setNodeMask(~0u);
            expectFresh("back again", 3 * framesInFlight);
            // The crowd grows past its batches' regions (they move, the buffers grow), then is still.
            for (unsigned a = 0; a < 12; ++a)
            {
                fc.actors.push_back(fc.placed(24 + a));
                fc.twins.push_back(fc.placed(24 + a));
                fc.group->addChild(fc.actors.back().get());
            }
            expectFresh("grown", 3 * framesInFlight);
            EXPECT_GT(fc.group->getStatistics().actorsKept, 10u) << name; // the test can fail: kept, not culled
        }
}
