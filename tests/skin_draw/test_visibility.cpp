// Visibility: a mesh no view sees does no skinning work (CPU path: no skinning; GPU path: no palette filled for
// upload) while its actor's pose, matrices and bound still follow the clip in update, so it reappears where it would
// have been; one frame's work is done once whatever the number of cameras; per-frame data is double-buffered by
// frame parity, never DYNAMIC; actors sharing a mesh keep their own state.
#include "SkinDrawTestUtil"

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const char* pathName(SkinnedMesh::SkinningPath path)
{
    return path == SkinnedMesh::GPU_SKINNING ? "GPU path" : "CPU path";
}

void lookAtCesiumMan(FrameDriver& driver) { driver.lookAt(osg::Vec3d(0, -5, 0.8), osg::Vec3d(0, 0, 0.8), osg::Vec3d(0, 0, 1)); }
void lookAway(FrameDriver& driver) { driver.lookAt(osg::Vec3d(0, -5, 0.8), osg::Vec3d(0, -10, 0.8), osg::Vec3d(0, 0, 1)); }

/** The state set holding the palette in a leaf's state (the last the mesh pushed), or null. */
const osg::StateSet* paletteOf(const FrameDriver::CulledLeaf& leaf)
{
    return leaf.stateSets.empty() ? nullptr : leaf.stateSets.back();
}

} // namespace

TEST(SkinnedMeshVisibility, AMeshNoViewSeesDoesNoSkinningWorkAndReappearsWhereItWouldHaveBeen)
{
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        // Two Cesium Men playing the same clip: one seen on every frame, one turned away from for ten.
        const RiggedModelActor hidden = readCesiumMan(path);
        const RiggedModelActor seen = readCesiumMan(path);
        FrameDriver hiddenDriver(hidden.sceneNode.get());
        FrameDriver seenDriver(seen.sceneNode.get());
        lookAtCesiumMan(seenDriver);
        lookAway(hiddenDriver);
        const SkinnedMesh& mesh = *hidden.skinnedMeshes[0];
        std::vector<double> lastDofs = hidden.actor->getDofs();
        for (unsigned frame = 1; frame <= 10; ++frame)
        {
            const double t = frame / 30.0;
            hiddenDriver.frame(t);
            seenDriver.frame(t);
            EXPECT_TRUE(hiddenDriver.culledDrawables().empty()) << pathName(path);
            // The player starts from the clip's first key on the first frame; the file's first key is at 0.04 s.
            if (frame >= 3)
            {
                EXPECT_NE(hidden.actor->getDofs(), lastDofs) << "the pose stopped at frame " << frame;
            }
            lastDofs = hidden.actor->getDofs();
        }
        SkinnedMesh::Statistics statistics = mesh.getStatistics(*hidden.actor);
        EXPECT_EQ(statistics.matrixUpdates, 10u) << pathName(path);
        EXPECT_EQ(statistics.cpuSkinnings, 0u) << pathName(path);
        EXPECT_EQ(statistics.paletteUploads, 0u) << pathName(path);
        EXPECT_EQ(seen.skinnedMeshes[0]->getStatistics(*seen.actor).cpuSkinnings +
                      seen.skinnedMeshes[0]->getStatistics(*seen.actor).paletteUploads,
                  10u);

        // Turned back to: drawn at once, as the actor seen all along is.
        lookAtCesiumMan(hiddenDriver);
        hiddenDriver.frame(11 / 30.0);
        seenDriver.frame(11 / 30.0);
        EXPECT_EQ(hidden.actor->getDofs(), seen.actor->getDofs());
        EXPECT_EQ(mesh.getSkinnedBound(*hidden.actor), seen.skinnedMeshes[0]->getSkinnedBound(*seen.actor));
        statistics = mesh.getStatistics(*hidden.actor);
        EXPECT_EQ(statistics.cpuSkinnings + statistics.paletteUploads, 1u) << pathName(path);
        const std::vector<const osg::Drawable*> hiddenDrawn = hiddenDriver.culledDrawables();
        const std::vector<const osg::Drawable*> seenDrawn = seenDriver.culledDrawables();
        ASSERT_EQ(hiddenDrawn.size(), 1u);
        ASSERT_EQ(seenDrawn.size(), 1u);
        if (path == SkinnedMesh::CPU_SKINNING)
        {
            const osg::Vec3Array& a = *static_cast<const osg::Vec3Array*>(hiddenDrawn[0]->asGeometry()->getVertexArray());
            const osg::Vec3Array& b = *static_cast<const osg::Vec3Array*>(seenDrawn[0]->asGeometry()->getVertexArray());
            EXPECT_EQ(maxDistance(a, b), 0.0);
        }
        else
        {
            const osg::Uniform* a = paletteOf(hiddenDriver.culledLeaves()[0])->getUniform("osgActor_palette");
            const osg::Uniform* b = paletteOf(seenDriver.culledLeaves()[0])->getUniform("osgActor_palette");
            ASSERT_TRUE(a && b);
            EXPECT_EQ(*a->getFloatArray(), *b->getFloatArray());
        }
    }
}

TEST(SkinnedMeshVisibility, AFrameIsSkinnedOnceWhateverTheNumberOfCameras)
{
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        const RiggedModelActor read = readCesiumMan(path);
        FrameDriver driver(read.sceneNode.get());
        lookAtCesiumMan(driver);
        driver.update(0.1);
        driver.cull();
        driver.cull(); // a second camera, the same frame
        const SkinnedMesh::Statistics statistics = read.skinnedMeshes[0]->getStatistics(*read.actor);
        EXPECT_EQ(statistics.cpuSkinnings + statistics.paletteUploads, 1u) << pathName(path);
        EXPECT_EQ(statistics.matrixUpdates, 1u);
    }
}

namespace {

/** What a leaf draws that changes with the pose: the CPU path's skinned positions or the GPU path's palette. */
std::vector<float> skinnedContentOf(const FrameDriver::CulledLeaf& leaf, SkinnedMesh::SkinningPath path)
{
    if (path == SkinnedMesh::CPU_SKINNING)
    {
        const osg::Vec3Array& positions = *static_cast<const osg::Vec3Array*>(leaf.drawable->asGeometry()->getVertexArray());
        std::vector<float> coordinates;
        for (const osg::Vec3f& p : positions) coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
        return coordinates;
    }
    const osg::Uniform* palette = paletteOf(leaf)->getUniform("osgActor_palette");
    return palette ? std::vector<float>(palette->getFloatArray()->begin(), palette->getFloatArray()->end())
                   : std::vector<float>();
}

/** A second camera on a scene whose cull comes late: it culls the frame its stamp holds, which seeFrame() sets to the
  * frame a driver is at, after that driver has gone on. */
class LateCamera
{
public:
    explicit LateCamera(osg::Node* scene) : _driver(scene), _stamp(new osg::FrameStamp)
    {
        _driver.sceneView().setFrameStamp(_stamp.get());
        lookAtCesiumMan(_driver);
    }
    void seeFrame(const FrameDriver& driver) { _stamp->setFrameNumber(driver.getFrameNumber()); }
    /** Its cull of that frame, and the one leaf it drew. */
    FrameDriver::CulledLeaf cull()
    {
        _driver.cull();
        const std::vector<FrameDriver::CulledLeaf> leaves = _driver.culledLeaves();
        EXPECT_EQ(leaves.size(), 1u);
        return leaves.empty() ? FrameDriver::CulledLeaf{nullptr, {}, false} : leaves[0];
    }

private:
    FrameDriver _driver;
    osg::ref_ptr<osg::FrameStamp> _stamp;
};

} // namespace

TEST(SkinnedMeshVisibility, ACullOfAnOlderFrameThanOneAlreadySkinnedNeitherSkinsAgainNorRewritesThatFramesBuffer)
{
    // osgViewer culls a camera added after its threads started on the draw thread: under DrawThreadPerContext the
    // cull of frame 1 for that camera can come after the main thread has updated and culled frame 2.
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        const RiggedModelActor read = readCesiumMan(path);
        FrameDriver driver(read.sceneNode.get());
        LateCamera lateCamera(read.sceneNode.get());
        lookAtCesiumMan(driver);

        driver.frame(1 / 30.0);
        lateCamera.seeFrame(driver);
        ASSERT_EQ(driver.culledLeaves().size(), 1u);
        const FrameDriver::CulledLeaf first = driver.culledLeaves()[0];
        const std::vector<float> firstContent = skinnedContentOf(first, path);
        ASSERT_FALSE(firstContent.empty());
        driver.frame(10 / 30.0);
        ASSERT_NE(skinnedContentOf(driver.culledLeaves()[0], path), firstContent) << "the pose must move for the test";

        const FrameDriver::CulledLeaf late = lateCamera.cull();
        ASSERT_TRUE(late.drawable);
        EXPECT_EQ(late.drawable, first.drawable) << pathName(path);
        EXPECT_EQ(paletteOf(late), paletteOf(first)) << pathName(path);
        EXPECT_EQ(skinnedContentOf(late, path), firstContent) << pathName(path) << ": frame 1's buffer was rewritten";
        const SkinnedMesh::Statistics statistics = read.skinnedMeshes[0]->getStatistics(*read.actor);
        EXPECT_EQ(statistics.matrixUpdates, 2u);
        EXPECT_EQ(statistics.cpuSkinnings + statistics.paletteUploads, 2u) << pathName(path);

        // The next frame is skinned as usual.
        driver.frame(11 / 30.0);
        EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(*read.actor).cpuSkinnings +
                      read.skinnedMeshes[0]->getStatistics(*read.actor).paletteUploads,
                  3u)
            << pathName(path);
    }
}

TEST(SkinnedMeshVisibility, ACullOfAnOlderFrameOnAPathThatFrameDidNotUseStillDrawsASkinnedBuffer)
{
    // Frame 1 on the GPU path, frame 2 switched to the CPU path, then a late cull of frame 1: there is no CPU buffer
    // of frame 1's parity yet, so it is skinned (from the current matrices) rather than drawn unskinned.
    const RiggedModelActor read = readCesiumMan(SkinnedMesh::GPU_SKINNING);
    FrameDriver driver(read.sceneNode.get());
    LateCamera lateCamera(read.sceneNode.get());
    lookAtCesiumMan(driver);
    driver.frame(1 / 30.0);
    lateCamera.seeFrame(driver);
    setSkinningPath(*read.actor, SkinnedMesh::CPU_SKINNING);
    driver.frame(10 / 30.0);
    const std::vector<float> current = skinnedContentOf(driver.culledLeaves()[0], SkinnedMesh::CPU_SKINNING);
    const FrameDriver::CulledLeaf late = lateCamera.cull();
    ASSERT_TRUE(late.drawable);
    EXPECT_NE(late.drawable, driver.culledLeaves()[0].drawable);
    EXPECT_EQ(skinnedContentOf(late, SkinnedMesh::CPU_SKINNING), current);
    const SkinnedMesh::Statistics statistics = read.skinnedMeshes[0]->getStatistics(*read.actor);
    EXPECT_EQ(statistics.paletteUploads, 1u);
    EXPECT_EQ(statistics.cpuSkinnings, 2u);
}

TEST(SkinnedMeshVisibility, FramesAlternateBetweenTwoBuffersAndNothingIsDynamic)
{
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        const RiggedModelActor read = readCesiumMan(path);
        FrameDriver driver(read.sceneNode.get());
        lookAtCesiumMan(driver);
        std::vector<FrameDriver::CulledLeaf> leaves;
        for (unsigned frame = 1; frame <= 3; ++frame)
        {
            driver.frame(frame / 30.0);
            ASSERT_EQ(driver.culledLeaves().size(), 1u);
            leaves.push_back(driver.culledLeaves()[0]);
            EXPECT_FALSE(leaves.back().dynamic) << pathName(path) << ": OSG would hold the next frame back";
        }
        // What frame 1 wrote, frame 2 leaves alone (the draw of frame 1 may still read it); frame 3 writes it again.
        if (path == SkinnedMesh::CPU_SKINNING)
        {
            EXPECT_NE(leaves[0].drawable, leaves[1].drawable);
            EXPECT_EQ(leaves[0].drawable, leaves[2].drawable);
            EXPECT_NE(leaves[0].drawable->asGeometry()->getVertexArray(), leaves[1].drawable->asGeometry()->getVertexArray());
        }
        else
        {
            EXPECT_EQ(leaves[0].drawable, leaves[1].drawable); // the static bind-pose geometry
            EXPECT_NE(paletteOf(leaves[0]), paletteOf(leaves[1]));
            EXPECT_EQ(paletteOf(leaves[0]), paletteOf(leaves[2]));
            EXPECT_TRUE(paletteOf(leaves[0])->getUniform("osgActor_palette"));
        }
    }
}

TEST(SkinnedMeshVisibility, ActorsSharingAMeshKeepTheirOwnPosesBoundsAndBuffers)
{
    const RiggedModelActor read = readCesiumMan(SkinnedMesh::CPU_SKINNING);
    // A shallow copy shares the geometry: the same SkinnedMesh below both actors.
    osg::ref_ptr<ActorNode> twin = static_cast<ActorNode*>(read.actor->clone(osg::CopyOp::SHALLOW_COPY));
    twin->setPreTranslation(osg::Vec3d(1.0, 0.0, 0.0));
    twin->removeController(twin->getControllers()[0]); // stands in its rest pose
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(read.sceneNode.get());
    scene->addChild(twin.get());
    FrameDriver driver(scene.get());
    driver.lookAt(osg::Vec3d(0.5, -6, 0.8), osg::Vec3d(0.5, 0, 0.8), osg::Vec3d(0, 0, 1));
    for (unsigned frame = 0; frame <= 15; ++frame) driver.frame(frame / 30.0);
    SkinnedMesh& mesh = *read.skinnedMeshes[0];
    ASSERT_EQ(findSkinnedMeshes(*twin), std::vector<SkinnedMesh*>{&mesh});
    const std::vector<const osg::Drawable*> drawn = driver.culledDrawables();
    ASSERT_EQ(drawn.size(), 2u);
    EXPECT_NE(drawn[0], drawn[1]);
    osg::ref_ptr<osg::Vec3Array> walking = new osg::Vec3Array, standing = new osg::Vec3Array;
    ASSERT_TRUE(mesh.computeSkinnedVertices(*read.actor, *walking));
    ASSERT_TRUE(mesh.computeSkinnedVertices(*twin, *standing));
    EXPECT_GT(maxDistance(*walking, *standing), 0.01);
    EXPECT_TRUE(holdsEvery(mesh.getSkinnedBound(*read.actor), *walking));
    EXPECT_TRUE(holdsEvery(mesh.getSkinnedBound(*twin), *standing));
    osg::BoundingBox both = mesh.getSkinnedBound(*read.actor);
    both.expandBy(mesh.getSkinnedBound(*twin));
    EXPECT_EQ(mesh.getBoundingBox(), both);
    // Each its own path.
    setSkinningPath(*twin, SkinnedMesh::GPU_SKINNING);
    EXPECT_EQ(mesh.getSkinningPath(*twin), SkinnedMesh::GPU_SKINNING);
    EXPECT_EQ(mesh.getSkinningPath(*read.actor), SkinnedMesh::CPU_SKINNING);
    driver.frame(16 / 30.0);
    EXPECT_EQ(mesh.getStatistics(*twin).paletteUploads, 1u);
    EXPECT_EQ(mesh.getStatistics(*read.actor).cpuSkinnings, 17u);
}
