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
