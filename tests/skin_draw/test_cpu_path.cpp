// The CPU path: what a cull traversal puts in the render stage is the skinned mesh, equal to a double-precision
// reference of linear blend skinning computed here from the file's own vertices and weights.
#include "SkinDrawTestUtil"

#include <osgActor/core/Clip>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The geometry a cull drew for a mesh of n vertices (the CPU path's output), or null. */
const osg::Geometry* drawnGeometryOf(const FrameDriver& driver, unsigned numVertices)
{
    for (const osg::Drawable* drawable : driver.culledDrawables())
    {
        const osg::Geometry* geometry = drawable->asGeometry();
        if (geometry && geometry->getVertexArray()->getNumElements() == numVertices) return geometry;
    }
    return nullptr;
}

/** The largest angle (radians) between the drawn normals and the reference's. */
double maxNormalAngle(const osg::Vec3Array& normals, const std::vector<ReferenceVertex>& reference)
{
    double largest = 0.0;
    for (std::size_t v = 0; v < normals.size(); ++v)
    {
        const glm::dvec3 drawn = glm::normalize(glm::dvec3(normals[v].x(), normals[v].y(), normals[v].z()));
        const double cosine = glm::dot(drawn, glm::normalize(reference[v].normal));
        largest = std::max(largest, std::acos(std::min(1.0, cosine)));
    }
    return largest;
}

} // namespace

TEST(SkinnedMeshCpuPath, CesiumManMatchesADoublePrecisionReferenceOnFramesOfItsClip)
{
    const RiggedModelActor read = readCesiumMan(SkinnedMesh::CPU_SKINNING);
    ASSERT_TRUE(read.actor);
    const SkinSource source = cesiumManSkinSource(read);
    const Skin& skin = *read.skinnedMeshes[0]->getSkin();
    const double diagonal = source.diagonal();
    FrameDriver driver(read.sceneNode.get());
    driver.lookAt(osg::Vec3d(0, -5, 0.8), osg::Vec3d(0, 0, 0.8), osg::Vec3d(0, 0, 1));
    const double duration = read.rigged.clips[0]->getDuration();
    unsigned frames = 0;
    for (double t = 0.0; t <= duration; t += duration / 24.0, ++frames)
    {
        driver.frame(t);
        const osg::Geometry* drawn = drawnGeometryOf(driver, skin.getNumVertices());
        ASSERT_TRUE(drawn) << "at t = " << t;
        const std::vector<ReferenceVertex> reference = referenceSkinning(source, skin, *read.actor);
        const osg::Vec3Array& positions = *static_cast<const osg::Vec3Array*>(drawn->getVertexArray());
        EXPECT_LE(maxDistance(positions, reference), 1e-5 * diagonal) << "at t = " << t;
        EXPECT_LE(maxNormalAngle(*static_cast<const osg::Vec3Array*>(drawn->getNormalArray()), reference), 1e-4)
            << "at t = " << t;
    }
    EXPECT_EQ(frames, 25u);
    EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(*read.actor).cpuSkinnings, 25u);
    EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(*read.actor).paletteUploads, 0u);
}

TEST(SkinnedMeshCpuPath, DualQuaternionAndEightInfluenceSkinsMatchTheirReferences)
{
    for (const SkinningMethod method : {SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion})
    {
        SyntheticActor made = makeRandomActor(12, 300, 8, 7u, method);
        made.mesh->setSkinningPath(SkinnedMesh::CPU_SKINNING);
        FrameDriver driver(made.actor.get());
        driver.lookAt(osg::Vec3d(0, -8, 0), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1), 60.0);
        for (double t : {0.0, 0.4, 1.1})
        {
            poseSynthetic(*made.actor, t);
            driver.frame(t);
            const osg::Geometry* drawn = drawnGeometryOf(driver, made.skin->getNumVertices());
            ASSERT_TRUE(drawn);
            const std::vector<ReferenceVertex> reference = referenceSkinning(made.source, *made.skin, *made.actor);
            EXPECT_LE(maxDistance(*static_cast<const osg::Vec3Array*>(drawn->getVertexArray()), reference),
                      1e-5 * made.source.diagonal());
        }
    }
}

TEST(SkinnedMeshCpuPath, OnDemandSkinningIsWhatTheCullDrew)
{
    const RiggedModelActor read = readCesiumMan(SkinnedMesh::CPU_SKINNING);
    FrameDriver driver(read.sceneNode.get());
    driver.lookAt(osg::Vec3d(0, -5, 0.8), osg::Vec3d(0, 0, 0.8), osg::Vec3d(0, 0, 1));
    driver.frame(0.7);
    const SkinnedMesh& mesh = *read.skinnedMeshes[0];
    const osg::Geometry* drawn = drawnGeometryOf(driver, mesh.getSkin()->getNumVertices());
    ASSERT_TRUE(drawn);
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    osg::ref_ptr<osg::Vec3Array> normals = new osg::Vec3Array;
    ASSERT_TRUE(mesh.computeSkinnedVertices(*read.actor, *positions, normals.get()));
    EXPECT_EQ(maxDistance(*positions, *static_cast<const osg::Vec3Array*>(drawn->getVertexArray())), 0.0);
    EXPECT_EQ(maxDistance(*normals, *static_cast<const osg::Vec3Array*>(drawn->getNormalArray())), 0.0);
}
