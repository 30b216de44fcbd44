// Skinned meshes of actors in an ActorGroup: their per-frame matrices and bounds are computed on the group's threads,
// right after each actor's update, and come out as the serial update traversal computes them: the same bounds, the
// same palettes uploaded, the same CPU-skinned vertices, frame after frame.
#include "SkinDrawTestUtil"

#include <osgActor/ActorGroup>

#include <osg/Uniform>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

constexpr unsigned kNumActors = 6;

/** kNumActors shallow copies of one Cesium Man (they share its skinned mesh), side by side, under the given group;
  * every other one skinned on the CPU. */
std::vector<ActorNode*> addCesiumMen(const RiggedModelActor& read, osg::Group& group)
{
    std::vector<ActorNode*> actors;
    for (unsigned a = 0; a < kNumActors; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(read.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.8 * a - 2.0, 0.0, 0.0));
        if (a % 2) setSkinningPath(*actor, SkinnedMesh::CPU_SKINNING);
        group.addChild(actor.get());
        actors.push_back(actor.get());
    }
    return actors;
}

/** The floats of every palette and every CPU-skinned vertex a cull collected, in the render graph's order. */
std::vector<float> culledSkinData(const FrameDriver& driver)
{
    std::vector<float> data;
    for (const FrameDriver::CulledLeaf& leaf : driver.culledLeaves())
    {
        for (const osg::StateSet* state : leaf.stateSets)
        {
            const osg::Uniform* palette = state ? state->getUniform("osgActor_palette") : nullptr;
            if (palette && palette->getFloatArray())
                data.insert(data.end(), palette->getFloatArray()->begin(), palette->getFloatArray()->end());
        }
        const osg::Geometry* geometry = leaf.drawable->asGeometry();
        const osg::Vec3Array* vertices =
            geometry ? dynamic_cast<const osg::Vec3Array*>(geometry->getVertexArray()) : nullptr;
        if (vertices && geometry->getComputeBoundingBoxCallback()) // the CPU path's output geometry
            for (const osg::Vec3& v : *vertices) data.insert(data.end(), {v.x(), v.y(), v.z()});
    }
    return data;
}

/** Reads the statistics of every actor when the group's update callback has run the actors' frames and before its
  * traversal reaches the meshes: a nested callback runs there. */
class MatrixUpdatesBeforeTraversal : public osg::NodeCallback
{
public:
    MatrixUpdatesBeforeTraversal(const SkinnedMesh& mesh, std::vector<ActorNode*> actors)
        : _mesh(mesh), _actors(std::move(actors))
    {
    }
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        updates.clear();
        for (const ActorNode* actor : _actors) updates.push_back(_mesh.getStatistics(*actor).matrixUpdates);
        traverse(node, nv);
    }
    std::vector<unsigned long long> updates;

private:
    const SkinnedMesh& _mesh;
    std::vector<ActorNode*> _actors;
};

} // namespace

TEST(ActorGroupSkinning, GivesEveryFrameTheBoundsPalettesAndVerticesOfTheSerialUpdate)
{
    const RiggedModelActor serialRead = readCesiumMan();
    const RiggedModelActor groupRead = readCesiumMan();
    osg::ref_ptr<osg::Group> serial = new osg::Group;
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    const std::vector<ActorNode*> serialActors = addCesiumMen(serialRead, *serial);
    const std::vector<ActorNode*> groupActors = addCesiumMen(groupRead, *group);
    FrameDriver serialDriver(serial.get());
    FrameDriver groupDriver(group.get());
    const SkinnedMesh& serialMesh = *serialRead.skinnedMeshes[0];
    const SkinnedMesh& groupMesh = *groupRead.skinnedMeshes[0];
    for (unsigned frame = 1; frame <= 12; ++frame)
    {
        const double t = frame / 30.0;
        serialDriver.frame(t);
        groupDriver.frame(t);
        for (unsigned a = 0; a < kNumActors; ++a)
        {
            const osg::BoundingBox expected = serialMesh.getSkinnedBound(*serialActors[a]);
            const osg::BoundingBox bound = groupMesh.getSkinnedBound(*groupActors[a]);
            ASSERT_TRUE(expected.valid());
            EXPECT_EQ(bound._min, expected._min) << "actor " << a << ", frame " << frame;
            EXPECT_EQ(bound._max, expected._max) << "actor " << a << ", frame " << frame;
            EXPECT_EQ(groupMesh.getStatistics(*groupActors[a]).matrixUpdates, frame);
        }
        // The mesh's bound, the union of its actors', dirtied as the serial update dirties it.
        EXPECT_EQ(groupMesh.getBoundingBox()._min, serialMesh.getBoundingBox()._min) << "frame " << frame;
        EXPECT_EQ(groupMesh.getBoundingBox()._max, serialMesh.getBoundingBox()._max) << "frame " << frame;
        const std::vector<float> expected = culledSkinData(serialDriver);
        ASSERT_GT(expected.size(), 1000u);
        EXPECT_EQ(culledSkinData(groupDriver), expected) << "frame " << frame;
    }
}

TEST(ActorGroupSkinning, ComputesTheSkinsMatricesWithTheActorsFramesBeforeTheTraversalReachesTheMeshes)
{
    const RiggedModelActor read = readCesiumMan();
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    const std::vector<ActorNode*> actors = addCesiumMen(read, *group);
    osg::ref_ptr<MatrixUpdatesBeforeTraversal> probe = new MatrixUpdatesBeforeTraversal(*read.skinnedMeshes[0], actors);
    group->getUpdateCallback()->setNestedCallback(probe.get());
    FrameDriver driver(group.get());
    // The first frame's traversal meets each mesh and lists it with its actor: from the second frame on, the
    // group's threads compute it with the actor's frame, before the traversal.
    for (unsigned frame = 1; frame <= 4; ++frame)
    {
        driver.frame(frame / 30.0);
        for (unsigned a = 0; a < kNumActors; ++a)
        {
            EXPECT_EQ(probe->updates[a], frame == 1 ? 0u : frame) << "actor " << a << ", frame " << frame;
            EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(*actors[a]).matrixUpdates, frame);
        }
    }
    // An actor whose mesh the traversal no longer meets drops it: the group's threads, which run before the
    // traversal, compute it once more (at the first frame without it), and then no more.
    ActorNode& last = *actors.back();
    osg::ref_ptr<osg::Node> skins = last.getChild(last.getNumChildren() - 1);
    ASSERT_TRUE(skins->asGeode() && skins->asGeode()->getDrawable(0) == read.skinnedMeshes[0].get());
    last.removeChild(skins.get());
    const unsigned long long before = read.skinnedMeshes[0]->getStatistics(last).matrixUpdates;
    for (unsigned frame = 5; frame <= 7; ++frame) driver.frame(frame / 30.0);
    EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(last).matrixUpdates, before + 1);
}
