// The GPU path against the CPU path on OSMesa: the positions the vertex shader computes, captured by transform
// feedback, against the core's SkinningJob at the same pose, within 1e-4 of the model's diagonal; in both profiles,
// with the palette in uniforms and in a texture buffer, for linear blend and dual quaternions, 4 and 8 influences,
// and a skin of more than 256 joints.
#include "SkinDrawTestUtil"
#include "TransformFeedbackCapture"

#include <gtest/gtest.h>

#include <iostream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const char* profileName(SkinningProfile profile)
{
    return profile == SkinningProfile::Core ? "core" : "compatibility";
}

/** Captures the GPU path at each time and compares it with the CPU skinning of the same pose; returns the largest
  * difference as a fraction of the diagonal. setPose(t) poses the actor before each frame's update (or nothing). */
template <class SetPose>
double gpuAgainstCpu(osg::Node* root, ActorNode& actor, SkinnedMesh& mesh, SkinningProfile profile, double diagonal,
                     const std::vector<double>& times, SetPose setPose)
{
    GpuSkinningCapture capture(root, mesh, profile);
    if (!capture.valid()) return 1.0;
    double largest = 0.0;
    for (double t : times)
    {
        setPose(t);
        const std::vector<osg::Vec3f> captured = capture.capture(t);
        EXPECT_FALSE(captured.empty()) << profileName(profile) << " at t = " << t;
        osg::ref_ptr<osg::Vec3Array> cpu = new osg::Vec3Array;
        EXPECT_TRUE(mesh.computeSkinnedVertices(actor, *cpu));
        largest = std::max(largest, maxDistanceToCpu(captured, mesh, *cpu) / diagonal);
    }
    EXPECT_EQ(mesh.getStatistics(actor).paletteUploads, times.size());
    EXPECT_EQ(mesh.getStatistics(actor).cpuSkinnings, 0u);
    return largest;
}

void reportDifference(const std::string& what, double difference)
{
    std::cout << "GPU against CPU, " << what << ": largest difference " << difference << " of the diagonal\n";
}

} // namespace

TEST(SkinnedMeshGpuPath, CesiumManMatchesTheCpuPathInBothProfilesAndBothPaletteStorages)
{
    for (const SkinningProfile profile : {SkinningProfile::Compatibility, SkinningProfile::Core})
        for (const SkinPaletteStorage storage : {SkinPaletteStorage::UniformArray, SkinPaletteStorage::TextureBuffer})
        {
            const RiggedModelActor read = readCesiumMan();
            SkinnedMesh& mesh = *read.skinnedMeshes[0];
            mesh.setPaletteStorage(storage);
            ASSERT_EQ(mesh.getEffectivePaletteStorage(), storage);
            const double diagonal = cesiumManSkinSource(read).diagonal();
            const double difference = gpuAgainstCpu(read.sceneNode.get(), *read.actor, mesh, profile, diagonal,
                                                    {0.0, 0.3, 0.9, 1.5}, [](double) {});
            EXPECT_LE(difference, 1e-4);
            reportDifference(std::string("Cesium Man, ") + profileName(profile) +
                                 (storage == SkinPaletteStorage::TextureBuffer ? ", texture buffer" : ", uniforms"),
                             difference);
        }
}

TEST(SkinnedMeshGpuPath, ASkinOfThreeHundredJointsTakesTheTextureBufferAndMatchesTheCpuPath)
{
    for (const SkinningProfile profile : {SkinningProfile::Compatibility, SkinningProfile::Core})
    {
        SyntheticActor made = makeChainActor(300);
        ASSERT_EQ(made.skin->getNumJoints(), 300u);
        EXPECT_EQ(made.mesh->getEffectivePaletteStorage(), SkinPaletteStorage::TextureBuffer);
        const double difference =
            gpuAgainstCpu(made.actor.get(), *made.actor, *made.mesh, profile, made.source.diagonal(), {0.2, 0.9},
                          [&made](double t) { poseSynthetic(*made.actor, t); });
        EXPECT_LE(difference, 1e-4);
        reportDifference(std::string("300-joint chain, ") + profileName(profile), difference);
    }
}

TEST(SkinnedMeshGpuPath, DualQuaternionAndEightInfluenceSkinsMatchTheCpuPath)
{
    for (const SkinningMethod method : {SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion})
        for (const SkinPaletteStorage storage : {SkinPaletteStorage::UniformArray, SkinPaletteStorage::TextureBuffer})
            for (const unsigned influences : {3u, 8u})
            {
                SyntheticActor made = makeRandomActor(20, 240, influences, 11u, method);
                made.mesh->setPaletteStorage(storage);
                const SkinningProgramKey key = made.mesh->getProgramKey(SkinningProfile::Compatibility);
                EXPECT_EQ(key.influences, influences > 4 ? 8u : 4u);
                EXPECT_EQ(key.method, method);
                const double difference = gpuAgainstCpu(
                    made.actor.get(), *made.actor, *made.mesh, SkinningProfile::Compatibility, made.source.diagonal(),
                    {0.5}, [&made](double t) { poseSynthetic(*made.actor, t); });
                EXPECT_LE(difference, 1e-4);
                reportDifference(std::string(method == SkinningMethod::DualQuaternion ? "dual quaternions" : "linear blend") +
                                     ", " + std::to_string(influences) + " influences" +
                                     (storage == SkinPaletteStorage::TextureBuffer ? ", texture buffer" : ", uniforms"),
                                 difference);
            }
}
