// The Assimp import reproduces the files' own motion: joint positions equal an independent evaluator of Assimp's
// scene (ReferenceAssimp) to 1e-5 of the model's height at every key time and to 1e-3 between keys, on Debian's
// assimp-testmodels files with skins and animations (Collada, FBX, DirectX), and the CPU-skinned vertices equal the
// reference's skinning at the key times.
#include "FidelityCheck"
#include "ImportTestUtil"
#include "ReferenceAssimp"
#include "SkinnedPositions"

#include <osgActor/import/AssimpReader>

using namespace osgActor;
using namespace osgActor::test;

namespace {

struct AssimpImport
{
    RiggedModelRead read;
    RiggedActor actor;
};

AssimpImport import(const std::string& path, const RiggedActorOptions& options)
{
    AssimpImport imported;
    imported.read = readAssimpFile(path);
    EXPECT_TRUE(imported.read) << imported.read.error;
    if (imported.read) imported.actor = buildRiggedActor(imported.read.model, options);
    EXPECT_TRUE(imported.actor) << imported.actor.error;
    return imported;
}

/** The clip made from the file's animation a (clips keep the model's animation names). */
ClipPtr clipOf(const AssimpImport& imported, unsigned a)
{
    for (const ClipPtr& clip : imported.actor.clips)
        if (clip->getName() == imported.read.model->animations[a].name) return clip;
    return ClipPtr();
}

/** The joints' positions against the reference, for animation a of the file. */
Fidelity measureAssimp(const std::string& path, unsigned a, const RiggedActorOptions& options = RiggedActorOptions())
{
    const ReferenceAssimp reference(path);
    EXPECT_TRUE(reference.loaded) << path;
    const AssimpImport imported = import(path, options);
    if (!imported.actor || !reference.loaded) return Fidelity();
    const ClipPtr clip = clipOf(imported, a);
    EXPECT_TRUE(clip) << path << ": animation " << a;
    if (!clip) return Fidelity();
    // Joint j is the reference's node of its name (names that are not unique are not compared).
    const RiggedModel& model = *imported.read.model;
    std::vector<int> referenceNode;
    for (int node : imported.actor.jointNodes)
    {
        const auto found = reference.byName.find(model.nodes[node].name);
        referenceNode.push_back(found == reference.byName.end() ? -1 : found->second);
    }
    return measureClip(imported.actor, *clip, reference.keyTimes(a), reference.height(referenceNode),
                       [&](unsigned j, double t, glm::dvec3& position) {
                           if (referenceNode[j] < 0) return false;
                           position = glm::dvec3(reference.world(referenceNode[j], int(a), t)[3]);
                           return true;
                       });
}

/** The largest distance between the CPU-skinned vertices of every skin and the reference's skinning, at every key time
  * of animation a, as a fraction of the skinned meshes' height (their extent at the first key). */
double skinnedError(const std::string& path, unsigned a)
{
    const ReferenceAssimp reference(path);
    const AssimpImport imported = import(path, RiggedActorOptions());
    const ClipPtr clip = clipOf(imported, a);
    if (!clip || imported.actor.skins.empty()) return 1.0;
    double worst = 0.0;
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
    const std::vector<double> times = reference.keyTimes(a);
    for (double t : times)
        for (std::size_t s = 0; s < imported.actor.skins.size(); ++s)
        {
            const std::vector<glm::dvec3> ours = skinnedPositions(imported.actor, s, *clip, t);
            const std::vector<glm::dvec3> expected = reference.skinned(unsigned(imported.actor.skins[s].mesh), int(a), t);
            EXPECT_EQ(ours.size(), expected.size());
            for (std::size_t v = 0; v < std::min(ours.size(), expected.size()); ++v)
            {
                worst = std::max(worst, glm::length(ours[v] - expected[v]));
                if (t != times.front()) continue;
                low = glm::min(low, expected[v]);
                high = glm::max(high, expected[v]);
            }
        }
    return worst / std::max({high.x - low.x, high.y - low.y, high.z - low.z});
}

std::string models(const std::string& file) { return assimpModels(file); }

} // namespace

TEST(AssimpFidelity, FbxArmaturesMoveAsTheFileSays)
{
    expectFaithful("animation_with_skeleton.fbx", measureAssimp(models("FBX/animation_with_skeleton.fbx"), 0));
    expectFaithful("huesitos.fbx", measureAssimp(models("FBX/huesitos.fbx"), 0));
    RiggedActorOptions lengthsZUp;
    lengthsZUp.rootScale = RootScale::InLengths;
    lengthsZUp.zUp = true;
    expectFaithful("huesitos.fbx (in lengths, Z up)", measureAssimp(models("FBX/huesitos.fbx"), 0, lengthsZUp));
}

TEST(AssimpFidelity, DirectXCharactersMoveAsTheFileSays)
{
    expectFaithful("BCN_Epileptic.X", measureAssimp(models("X/BCN_Epileptic.X"), 0));
    for (unsigned a = 0; a < 2; ++a) // Wuson_Run, Wuson_Walk (Wuson_Bind holds one pose)
        expectFaithful("Testwuson.X animation " + std::to_string(a), measureAssimp(models("X/Testwuson.X"), a));
}

TEST(AssimpFidelity, ColladaBoneMovesAsTheFileSays)
{
    expectFaithful("box_nested_animation.dae", measureAssimp(models("Collada/box_nested_animation.dae"), 0));
}

TEST(AssimpFidelity, JointsThatSkinNoVertexKeepTheirRestTransformFromTheNodeTree)
{
    // chain_hand.x: chain.x with Hand (1 up from Lower, turned a quarter about Z) and Finger (half a unit along
    // Hand's X) below Lower. Neither weighs a vertex, so Assimp gives them no bone (no offset matrix); Finger turns
    // about its own Y (which moves no joint's position), Hand is not animated.
    const std::string path = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/import/data/directx/chain_hand.x";
    expectFaithful("chain_hand.x", measureAssimp(path, 0));
    const AssimpImport imported = import(path, RiggedActorOptions());
    ASSERT_TRUE(imported.actor);
    const ActorDefinition& definition = *imported.actor.definition;
    const int hand = definition.findJoint("Hand");
    const int finger = definition.findJoint("Finger");
    ASSERT_GE(hand, 0); // a joint because Finger, below it, moves
    ASSERT_GE(finger, 0);
    EXPECT_EQ(definition.getNumJointDofs(unsigned(hand)), 0u);
    EXPECT_GT(definition.getNumJointDofs(unsigned(finger)), 0u);
    ASSERT_EQ(imported.actor.skins.size(), 1u);
    EXPECT_EQ(imported.actor.skins[0].skin->getNumJoints(), 2u); // Upper and Lower only
    // At 0 s (the rest) Hand is 3 up and Finger half a unit further along Hand's X, which Hand's quarter turn points
    // up. At 1 s Lower, 2 up, has turned a quarter about X, which takes +Y to +Z (and the quad's vertex half a unit
    // below Lower to -Z: osgactorconv_dump_x_skinned): both hang from Lower as the node tree has them, 1 and 1.5
    // along +Z.
    const ClipPtr clip = clipOf(imported, 0);
    ASSERT_TRUE(clip);
    const std::vector<glm::dvec3> rest = importedPositions(imported.actor, *clip, 0.0);
    EXPECT_NEAR(glm::length(rest[unsigned(hand)] - glm::dvec3(0.0, 3.0, 0.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(rest[unsigned(finger)] - glm::dvec3(0.0, 3.5, 0.0)), 0.0, 1e-6);
    const std::vector<glm::dvec3> bent = importedPositions(imported.actor, *clip, 1.0);
    EXPECT_NEAR(glm::length(bent[unsigned(hand)] - glm::dvec3(0.0, 2.0, 1.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(bent[unsigned(finger)] - glm::dvec3(0.0, 2.0, 1.5)), 0.0, 1e-6);
}

TEST(AssimpFidelity, SkinnedVerticesFollowTheBonesAsAssimpsOffsetsSay)
{
    for (const char* file : {"FBX/animation_with_skeleton.fbx", "FBX/huesitos.fbx", "X/BCN_Epileptic.X",
                             "Collada/box_nested_animation.dae"})
    {
        const double error = skinnedError(models(file), 0);
        EXPECT_LE(error, 1e-5) << file;
        std::cout << file << ": skinned vertices within " << error << " of the height at every key time\n";
    }
}
