// What the mapping makes of a rigged model: joints and their order, DOFs, offsets, the root scale, skins bound by
// joint name, rigid meshes on their joints, and the warnings for what the DOF model cannot hold.
#include "GltfTestFile"
#include "ImportTestUtil"
#include "TestMath"

#include <osgActor/core/ActorPose>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/import/GltfReader>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/UniformClip>

#include <glm/ext/quaternion_trigonometric.hpp>

using namespace osgActor;
using namespace osgActor::test;

namespace {

RiggedActor import(const std::string& path, const RiggedActorOptions& options = RiggedActorOptions())
{
    const RiggedModelRead read = readGltfFile(path);
    EXPECT_TRUE(read.model) << read.error;
    return read.model ? buildRiggedActor(read.model, options) : RiggedActor();
}


} // namespace

TEST(RiggedActorMapping, RefusesAModelWithNothingToMove)
{
    auto model = std::make_shared<RiggedModel>();
    model->sourceFile = "empty.gltf";
    const RiggedActor actor = buildRiggedActor(model);
    EXPECT_FALSE(actor.definition);
    EXPECT_EQ(actor.error, "empty.gltf: nothing to make an actor of: no skin, no animation and no mesh");
    EXPECT_FALSE(buildRiggedActor(nullptr));
}

TEST(RiggedActorMapping, CesiumManJointsAreTheSkinsJointsAndTheirAncestorsParentsFirst)
{
    const RiggedActor actor = import(cesiumMan());
    ASSERT_TRUE(actor) << actor.error;
    const ActorDefinition& definition = *actor.definition;
    EXPECT_EQ(definition.getName(), "CesiumMan");
    ASSERT_EQ(definition.getNumJoints(), 21u); // 19 skin joints, Armature and Z_UP
    EXPECT_EQ(definition.getJointName(0), "Z_UP");
    EXPECT_EQ(definition.getJointName(1), "Armature");
    EXPECT_EQ(definition.getJointName(2), "Skeleton_torso_joint_1");
    for (unsigned j = 1; j < definition.getNumJoints(); ++j) EXPECT_LT(definition.getParent(j), int(j));
    EXPECT_EQ(definition.findJoint("Cesium_Man"), -1); // the skinned mesh's node does not move the skin
    // Every skin joint rotates and, animated in translation, slides; the ancestors are fixed.
    EXPECT_EQ(definition.getNumJointDofs(0), 0u);
    EXPECT_EQ(definition.getNumJointDofs(1), 0u);
    EXPECT_EQ(definition.getDofMask(2), DofMask(kRotationDofs | kTranslationDofs));
    EXPECT_EQ(definition.getTranslationMode(2), TranslationMode::BeforeRotation);
    // The rest pose is the file's: the offset holds the node's rest translation and rotation.
    const RiggedModelRead read = readGltfFile(cesiumMan());
    EXPECT_TRUE(vectorsNear(definition.getOffsetTranslation(2), read.model->nodes[3].translation, 1e-15));
    EXPECT_NEAR(std::abs(glm::dot(definition.getOffsetRotation(2), read.model->nodes[3].rotation)), 1.0, 1e-15);
    for (double value : definition.getDefaultDofs()) EXPECT_EQ(value, 0.0);
    // No root scale: nothing above the actor.
    EXPECT_TRUE(matricesNear(actor.modelToScene, glm::dmat4(1.0)));
    ASSERT_EQ(actor.clips.size(), 1u);
    EXPECT_EQ(actor.clips[0]->getName(), "animation0");
    EXPECT_NEAR(actor.clips[0]->getDuration(), 2.0, 1e-7);
    EXPECT_GT(actor.modelHeight, 1.0);
    EXPECT_LT(actor.modelHeight, 2.0);
}

TEST(RiggedActorMapping, CesiumManSkinIsBoundByJointName)
{
    const RiggedActor actor = import(cesiumMan());
    ASSERT_TRUE(actor) << actor.error;
    ASSERT_EQ(actor.skins.size(), 1u);
    const SkinnedPrimitive& skinned = actor.skins[0];
    EXPECT_EQ(skinned.mesh, 0);
    EXPECT_EQ(skinned.primitive, 0);
    EXPECT_EQ(skinned.node, 2);
    ASSERT_TRUE(skinned.skin);
    const Skin& skin = *skinned.skin;
    ASSERT_EQ(skin.getNumJoints(), 19u);
    EXPECT_EQ(skin.getNumVertices(), 3273u);
    EXPECT_EQ(skin.getJointName(0), "Skeleton_torso_joint_1");
    const SkinBinding binding = bindSkinToDefinition(skin, *actor.definition);
    ASSERT_TRUE(binding) << binding.error;
    // At rest, every joint's skinning matrix (model matrix times inverse bind) is what the file gives: its scene
    // matrix times its inverse bind matrix.
    ActorPose rest(actor.definition);
    rest.updateMatrices();
    const RiggedModel& model = *actor.model;
    for (unsigned j = 0; j < skin.getNumJoints(); ++j)
    {
        const glm::dmat4 skinning = rest.getModelMatrix(binding.definitionJoints[j]) * skin.getInverseBindMatrix(j);
        const glm::dmat4 expected = restSceneMatrix(model, model.skins[0].joints[j]) * model.skins[0].inverseBindMatrices[j];
        EXPECT_TRUE(matricesNear(skinning, expected, 1e-6)) << skin.getJointName(j);
    }
    EXPECT_TRUE(actor.rigidMeshes.empty());
}

TEST(RiggedActorMapping, ARigidMeshHangsOnItsNodesJoint)
{
    const RiggedActor actor = import(gltf2("BoxTextured-glTF/BoxTextured.gltf"));
    ASSERT_TRUE(actor) << actor.error;
    ASSERT_EQ(actor.definition->getNumJoints(), 2u); // the mesh's node and its parent
    EXPECT_EQ(actor.definition->getNumDofs(), 0u);
    ASSERT_EQ(actor.rigidMeshes.size(), 1u);
    EXPECT_EQ(actor.rigidMeshes[0].joint, 1u);
    EXPECT_EQ(actor.rigidMeshes[0].mesh, 0);
    EXPECT_TRUE(matricesNear(actor.rigidMeshes[0].jointFromMesh, glm::dmat4(1.0)));
    EXPECT_TRUE(actor.clips.empty());
}

TEST(RiggedActorMapping, TheRootScaleGoesAboveTheActorOrIntoItsLengths)
{
    GltfTestFile file;
    const int times = file.addFloats({0, 1}, "SCALAR");
    const int moves = file.addFloats({0, 0, 0, 100, 0, 0}, "VEC3");
    const std::string body = R"("scenes":[{"nodes":[0]}],"nodes":[{"name":"armature","scale":[0.01,0.01,0.01],"children":[1]},
        {"name":"hips","translation":[0,90,0]}],"animations":[{"channels":[{"sampler":0,"target":{"node":1,"path":"translation"}}],
        "samplers":[{"input":)" + std::to_string(times) + R"(,"output":)" + std::to_string(moves) + "}]}]";
    file.write(written("armature.gltf"), body);

    const RiggedActor above = import(written("armature.gltf"));
    ASSERT_TRUE(above) << above.error;
    EXPECT_NEAR(above.modelToScene[0][0], 0.01, 1e-12);
    EXPECT_NEAR(above.modelToScene[2][2], 0.01, 1e-12);
    EXPECT_TRUE(vectorsNear(above.definition->getOffsetTranslation(1), glm::dvec3(0, 90, 0), 1e-12)); // centimetres

    RiggedActorOptions options;
    options.rootScale = RootScale::InLengths;
    const RiggedActor lengths = import(written("armature.gltf"), options);
    ASSERT_TRUE(lengths) << lengths.error;
    EXPECT_TRUE(matricesNear(lengths.modelToScene, glm::dmat4(1.0)));
    EXPECT_TRUE(vectorsNear(lengths.definition->getOffsetTranslation(1), glm::dvec3(0, 0.9, 0), 1e-12)); // metres
    // Its tx at the end of the clip: 100 centimetres, 1 metre.
    const Clip& clip = *lengths.clips.at(0);
    EXPECT_NEAR(clip.getKeyValue(unsigned(clip.findChannel("hips.tx")), 1), 1.0, 1e-12);
}

TEST(RiggedActorMapping, WarnsAboutAnimatedScaleAndNonUniformScaleAboveJoints)
{
    GltfTestFile file;
    const int times = file.addFloats({0, 1}, "SCALAR");
    const int scales = file.addFloats({1, 1, 1, 2, 2, 2}, "VEC3");
    const int still = file.addFloats({1, 1, 1, 1.000001f, 1, 1}, "VEC3");
    const auto n = [](int i) { return std::to_string(i); };
    const std::string body = R"("scenes":[{"nodes":[0]}],"nodes":[{"name":"root","scale":[1,2,1],"children":[1]},{"name":"arm","children":[2]},{"name":"hand"}],"skins":[{"joints":[1,2]}],
        "animations":[{"name":"grow","channels":[{"sampler":0,"target":{"node":1,"path":"scale"}},{"sampler":1,"target":{"node":2,"path":"scale"}}],
        "samplers":[{"input":)" + n(times) + R"(,"output":)" + n(scales) + R"(},{"input":)" + n(times) + R"(,"output":)" + n(still) + "}]}]";
    file.write(written("scales.gltf"), body);
    const RiggedActor actor = import(written("scales.gltf"));
    ASSERT_TRUE(actor) << actor.error;
    EXPECT_TRUE(anyWarningSays(actor.warnings, "animations[0] 'grow': the scale of nodes[1] 'arm' is animated"));
    EXPECT_FALSE(anyWarningSays(actor.warnings, "nodes[2] 'hand' is animated")); // within 1e-5 of its rest scale
    EXPECT_TRUE(anyWarningSays(actor.warnings, "nodes[0] 'root': its scale (1.000000, 2.000000, 1.000000) is not uniform"));
    EXPECT_TRUE(anyWarningSays(actor.warnings, "'grow' moves no joint and is left out"));
    EXPECT_TRUE(actor.clips.empty());
}

TEST(RiggedActorMapping, AnAnimatedScaleOnANodeThatIsNoJointIsWarnedAboutAndTheRestRead)
{
    // "prop" is no joint (no skin names it, nothing it carries moves, only its scale is animated): the scale channel
    // is warned about and skipped; before, the mapping looked up the joint of that node, which it does not have.
    GltfTestFile file;
    const int times = file.addFloats({0, 1}, "SCALAR");
    const int scales = file.addFloats({1, 1, 1, 2, 2, 2}, "VEC3");
    const int turns = file.addFloats({0, 0, 0, 1, 0, 0, 0.7071068f, 0.7071068f}, "VEC4");
    const auto n = [](int i) { return std::to_string(i); };
    const std::string body = R"("scenes":[{"nodes":[0,2]}],"nodes":[{"name":"arm","children":[1]},{"name":"hand"},{"name":"prop"}],"skins":[{"joints":[0,1]}],
        "animations":[{"name":"wave","channels":[{"sampler":0,"target":{"node":2,"path":"scale"}},{"sampler":1,"target":{"node":0,"path":"rotation"}}],
        "samplers":[{"input":)" + n(times) + R"(,"output":)" + n(scales) + R"(},{"input":)" + n(times) + R"(,"output":)" + n(turns) + "}]}]";
    file.write(written("prop_scale.gltf"), body);
    const RiggedActor actor = import(written("prop_scale.gltf"));
    ASSERT_TRUE(actor) << actor.error;
    EXPECT_TRUE(anyWarningSays(actor.warnings, "animations[0] 'wave': the scale of nodes[2] 'prop' is animated"));
    ASSERT_EQ(actor.clips.size(), 1u);
    EXPECT_GE(actor.clips[0]->findChannel("arm.rz"), 0);
    EXPECT_EQ(actor.definition->findJoint("prop"), -1);
}

TEST(RiggedActorMapping, KeysLandOnTheFilesKeyTimesAndResampleBetween)
{
    const RiggedActor actor = import(gltf2("simple_skin/simple_skin.gltf"));
    ASSERT_TRUE(actor) << actor.error;
    const Clip& clip = *actor.clips.at(0);
    const RiggedModelRead read = readGltfFile(gltf2("simple_skin/simple_skin.gltf"));
    const std::vector<double>& fileTimes = read.model->animations[0].channels[0].times;
    // The rotated joint (node2) turns about Z only: its rz channel has every file key time among its keys, and more
    // keys between them where the slerp is not linear in the angle... which about one axis it is: no more keys.
    const int rz = clip.findChannel("node2.rz");
    ASSERT_GE(rz, 0);
    std::vector<double> keys;
    for (unsigned k = 0; k < clip.getNumKeys(unsigned(rz)); ++k) keys.push_back(clip.getKeyTime(unsigned(rz), k));
    for (double t : fileTimes) EXPECT_NE(std::find(keys.begin(), keys.end(), t), keys.end()) << t;
    EXPECT_EQ(keys.size(), fileTimes.size());
}

TEST(RiggedActorMapping, ASampledClipHasAFrameEveryStepFromTheFirstKeyToTheLast)
{
    const RiggedActor actor = import(cesiumMan());
    ASSERT_TRUE(actor) << actor.error;
    const Clip& clip = *actor.clips.at(0);
    const ClipBuildResult sampled = sampleClipUniformly(clip, 0.04166661947965622, 2.0, 30.0);
    ASSERT_TRUE(sampled) << sampled.error;
    EXPECT_EQ(sampled.clip->getNumFrames(), 59u); // 0.0417 + k / 30 <= 2: k = 0..58
    EXPECT_EQ(sampled.clip->getFrameRate(), 30.0);
    EXPECT_FALSE(sampleClipUniformly(clip, 1.0, 0.5, 30.0));
    EXPECT_FALSE(sampleClipUniformly(clip, 0.0, 1.0, 0.0));
}
