// The osgAnimation import (osgActor/OsgAnimationImport): scenes made with osgAnimation become rigged models and actors
// that move as osgAnimation moves them. The reference is osgAnimation itself (ReferenceOsgAnimation): the same
// scene played by its BasicAnimationManager through update traversals. Scenes: the committed leg.osgt (made in code
// by OsgAnimationFixture, checked here to be current), and what OSG's own Collada plugin (osgdb_dae) makes of
// Debian's assimp-testmodels files.
#include "FidelityCheck"
#include "ImportTestUtil"
#include "OsgAnimationFixture"
#include "ReferenceOsgAnimation"
#include "SkinnedPositions"

#include <osgActor/OsgAnimationImport>
#include <osgActor/import/RiggedModelFile>

#include <osg/MatrixTransform>
#include <osg/ShapeDrawable>
#include <osgDB/ReadFile>
#include <osgDB/WriteFile>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

std::string legFile() { return std::string(OSGACTOR_TEST_SOURCE_DIR) + "/import/data/osganimation/leg.osgt"; }

std::string readText(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/** The scene's conversion refused, with the name and the place, and nothing half-built. */
void expectRefused(const osg::Node& scene, const std::string& place, const std::string& what)
{
    const RiggedModelRead read = convertOsgAnimationScene(scene, "scene.osgt");
    EXPECT_FALSE(read.model);
    EXPECT_TRUE(read.warnings.empty());
    EXPECT_EQ(read.error.rfind("scene.osgt: " + place, 0), 0u) << read.error;
    EXPECT_NE(read.error.find(what), std::string::npos) << read.error;
}

struct Measured
{
    Fidelity fidelity;
    /** The largest distance between our CPU-skinned vertices and osgAnimation's, at the key times, as a fraction of
      * the height. */
    double skinned = 0.0;
};

/** A node's world position (the root's space) in osgAnimation's pose with every transform above it made rigid: its
  * matrix's translation and the rotation of its linear part's polar decomposition (osg::Matrixd::decompose, OSG's
  * own), the stretch left out. Where osgAnimation blends matrix keys element by element, that is the motion without
  * the blend's shrink. */
glm::dvec3 positionWithoutStretch(const osg::Node& node)
{
    const osg::NodePath path = node.getParentalNodePaths()[0];
    osg::Matrixd world;
    for (const osg::Node* above : path)
    {
        const osg::MatrixTransform* transform = dynamic_cast<const osg::MatrixTransform*>(above);
        if (!transform) continue;
        osg::Vec3d translation, scale;
        osg::Quat rotation, scaleOrientation;
        transform->getMatrix().decompose(translation, rotation, scale, scaleOrientation);
        world = osg::Matrixd::rotate(rotation) * osg::Matrixd::translate(translation) * world;
    }
    const osg::Vec3d p = world.getTrans();
    return glm::dvec3(p.x(), p.y(), p.z());
}

/** Converts the scene, plays its animation a in osgAnimation, and compares: joint positions at the key times and
  * between (as osgAnimation has them, or with the stretch of its transforms left out: positionWithoutStretch()),
  * skinned vertices at the key times. */
Measured measureAgainstOsgAnimation(osg::Node& scene, unsigned a, bool withoutStretch = false)
{
    Measured measured;
    std::vector<const osg::Node*> sources;
    const RiggedModelRead read = convertOsgAnimationScene(scene, "scene", &sources);
    EXPECT_TRUE(read) << read.error;
    if (!read) return measured;
    const RiggedActor actor = buildRiggedActor(read.model);
    EXPECT_TRUE(actor) << actor.error;
    if (!actor) return measured;
    ClipPtr clip;
    for (const ClipPtr& each : actor.clips)
        if (each->getName() == read.model->animations[a].name) clip = each;
    EXPECT_TRUE(clip);
    if (!clip) return measured;

    OsgAnimationPlayback playback(scene, a);
    const std::vector<double> times = playback.keyTimes();
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
    for (int node : actor.jointNodes)
    {
        const glm::dvec3 p = OsgAnimationPlayback::position(*sources[node]);
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const double height = std::max({high.x - low.x, high.y - low.y, high.z - low.z});
    double posed = -1.0;
    measured.fidelity = measureClip(actor, *clip, times, height, [&](unsigned j, double t, glm::dvec3& position) {
        if (t != posed) playback.update(posed = t);
        const osg::Node& node = *sources[actor.jointNodes[j]];
        position = withoutStretch ? positionWithoutStretch(node) : OsgAnimationPlayback::position(node);
        return true;
    });
    for (double t : times)
    {
        playback.update(t);
        for (std::size_t s = 0; s < actor.skins.size(); ++s)
        {
            const auto& rig = dynamic_cast<const osgAnimation::RigGeometry&>(*sources[actor.skins[s].node]);
            const std::vector<glm::dvec3> theirs = OsgAnimationPlayback::skinned(rig);
            const std::vector<glm::dvec3> ours = skinnedPositions(actor, s, *clip, t);
            EXPECT_EQ(ours.size(), theirs.size());
            for (std::size_t v = 0; v < std::min(ours.size(), theirs.size()); ++v)
            {
                if (std::getenv("DEBUGSKIN") && glm::length(ours[v] - theirs[v]) / height > 1e-5)
                    std::cout << "t " << t << " v " << v << " ours " << ours[v].x << " " << ours[v].y << " " << ours[v].z
                              << " theirs " << theirs[v].x << " " << theirs[v].y << " " << theirs[v].z << "\n";
                measured.skinned = std::max(measured.skinned, glm::length(ours[v] - theirs[v]) / height);
            }
        }
    }
    return measured;
}

void expectLikeOsgAnimation(const std::string& what, const Measured& measured)
{
    expectFaithful(what, measured.fidelity);
    EXPECT_LE(measured.skinned, 1e-5) << what;
    std::cout << what << ": skinned vertices within " << measured.skinned << " of the height at every key time\n";
}

/** osgAnimation interpolates a matrix channel element by element: between keys whose rotations differ by an angle
  * a, a point d away from the bone moves along the chord, off the arc a rigid turn takes it on, by up to
  * d (1 - cos(a / 2)). The sum over an animation's matrix channels of the largest such amount for d = height: how far
  * osgAnimation's joints may stray from a rigid interpolation of the same keys (which the import does). */
double matrixChordBound(const osgAnimation::Animation& animation, double height)
{
    double bound = 0.0;
    for (const auto& channel : animation.getChannels())
    {
        const auto* sampler = dynamic_cast<const osgAnimation::MatrixLinearSampler*>(channel->getSampler());
        if (!sampler) continue;
        double largest = 0.0;
        const auto& keys = *sampler->getKeyframeContainerTyped();
        for (std::size_t k = 0; k + 1 < keys.size(); ++k)
        {
            const osg::Quat a = keys[k].getValue().getRotate(), b = keys[k + 1].getValue().getRotate();
            const double cosine = std::min(1.0, std::abs(a.x() * b.x() + a.y() * b.y() + a.z() * b.z() + a.w() * b.w()));
            largest = std::max(largest, 1.0 - std::cos(std::acos(cosine))); // 1 - cos(angle / 2)
        }
        bound += largest * height;
    }
    return bound;
}

osg::ref_ptr<osg::Node> readScene(const std::string& path)
{
    osg::ref_ptr<osg::Node> scene = osgDB::readRefNodeFile(path);
    EXPECT_TRUE(scene) << path;
    return scene;
}

} // namespace

// --- bad scenes first ---

TEST(OsgAnimationImport, RefusesASceneWithoutASkeleton)
{
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->setName("Ground");
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(new osg::ShapeDrawable(new osg::Box));
    root->addChild(geode.get());
    expectRefused(*root, "Group 'Ground'", "holds no osgAnimation::Skeleton");
}

TEST(OsgAnimationImport, RefusesAFileOsgCannotRead)
{
    const RiggedModelRead read = readOsgAnimationFile(written("missing.osgt"));
    EXPECT_FALSE(read.model);
    EXPECT_EQ(read.error.rfind(written("missing.osgt") + ": OSG cannot read it", 0), 0u) << read.error;
}

TEST(OsgAnimationImport, RefusesACycleInTheSceneGraph)
{
    LegScene scene = makeLegScene();
    scene.ankle->addChild(scene.hip.get());
    expectRefused(*scene.root, "Bone 'Hip'", "is its own ancestor");
    scene.ankle->removeChild(scene.hip.get()); // no reference cycle left to leak
}

TEST(OsgAnimationImport, RefusesInfluencesOnVerticesThatDoNotExist)
{
    LegScene scene = makeLegScene();
    (*scene.leg->getInfluenceMap())["Knee"].push_back(osgAnimation::VertexIndexWeight(99u, 0.5f));
    expectRefused(*scene.root, "RigGeometry 'Leg'", "bone 'Knee' weights vertex 99 of 19");
}

TEST(OsgAnimationImport, RefusesNegativeWeights)
{
    LegScene scene = makeLegScene();
    (*scene.leg->getInfluenceMap())["Ankle"].push_back(osgAnimation::VertexIndexWeight(3u, -0.5f));
    expectRefused(*scene.root, "RigGeometry 'Leg'", "bone 'Ankle' has a weight that is not a finite number >= 0");
}

TEST(OsgAnimationImport, RefusesVerticesThatAreNotFinite)
{
    LegScene scene = makeLegScene();
    (*static_cast<osg::Vec3Array*>(scene.legSource->getVertexArray()))[5].y() = std::nanf("");
    expectRefused(*scene.root, "RigGeometry 'Leg'", "a vertex is not finite");
}

TEST(OsgAnimationImport, RefusesKeyTimesThatGoBack)
{
    LegScene scene = makeLegScene();
    osgAnimation::Animation& walk = *scene.manager->getAnimationList()[0];
    for (const auto& channel : walk.getChannels())
        if (auto* knee = dynamic_cast<osgAnimation::FloatLinearChannel*>(channel.get()); knee && knee->getTargetName() == "Knee")
            (*knee->getSamplerTyped()->getKeyframeContainerTyped())[2].setTime(0.25);
    expectRefused(*scene.root, "animations[0] 'Walk'.channel 'Knee.rotateX'", "key times are not strictly increasing at key 2");
}

TEST(OsgAnimationImport, RefusesATransformInAnAbsoluteFrame)
{
    LegScene scene = makeLegScene();
    scene.knee->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    expectRefused(*scene.root, "Bone 'Knee'", "absolute reference frame");
}

TEST(OsgAnimationImport, SaysWhatItLeavesOut)
{
    LegScene scene = makeLegScene();
    (*scene.leg->getInfluenceMap())["Tail"].push_back(osgAnimation::VertexIndexWeight(0u, 0.5f));
    auto stray = makeChannel<osgAnimation::FloatLinearChannel>("Nobody", "rotateX");
    stray->getOrCreateSampler()->getOrCreateKeyframeContainer()->push_back(osgAnimation::FloatKeyframe(0.0, 1.0f));
    scene.manager->getAnimationList()[0]->addChannel(stray.get());
    osg::ref_ptr<osg::Geode> ground = new osg::Geode;
    ground->addDrawable(new osg::ShapeDrawable(new osg::Box));
    scene.root->addChild(ground.get());
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "scene.osgt");
    ASSERT_TRUE(read) << read.error;
    EXPECT_TRUE(anyWarningSays(read.warnings, "scene.osgt: RigGeometry 'Leg': bone 'Tail' of its influences is not in its Skeleton"));
    EXPECT_TRUE(anyWarningSays(read.warnings, "scene.osgt: animations[0] 'Walk'.channels[5] 'Nobody.rotateX': targets no UpdateMatrixTransform"));
    EXPECT_TRUE(anyWarningSays(read.warnings, "scene.osgt: 1 drawables outside every osgAnimation::Skeleton are left out"));
}

// --- what the leg maps to ---

TEST(OsgAnimationImport, TheLegsNodesAreItsTransformsWithTheirStackedRestMatrices)
{
    LegScene scene = makeLegScene();
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "leg");
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    std::vector<std::string> names;
    for (const RiggedNode& node : model.nodes) names.push_back(node.name);
    EXPECT_EQ(names, (std::vector<std::string>{"Rig", "Skeleton", "Hip", "Knee", "Ankle", "Foot", "LegPlacement", "Leg"}));
    EXPECT_EQ(model.sceneRoots, std::vector<int>{0});
    const std::vector<int> parents{-1, 0, 1, 2, 3, 4, 1, 6};
    for (std::size_t n = 0; n < parents.size(); ++n) EXPECT_EQ(model.nodes[n].parent, parents[n]) << names[n];
    // The skeleton's matrix: scale 0.5, then up 2; the knee's stack: down 1, no turn.
    EXPECT_NEAR(model.nodes[1].scale.x, 0.5, 1e-12);
    EXPECT_NEAR(model.nodes[1].translation.z, 2.0, 1e-12);
    EXPECT_NEAR(model.nodes[3].translation.z, -1.0, 1e-12);
    EXPECT_NEAR(model.nodes[6].translation.x, 0.3, 1e-7);
    EXPECT_EQ(model.nodes[5].mesh, 0); // the foot: rigid, on the ankle
    EXPECT_EQ(model.nodes[5].skin, -1);
    EXPECT_EQ(model.nodes[7].mesh, 1);
    EXPECT_EQ(model.nodes[7].skin, 0);
}

TEST(OsgAnimationImport, TheLegsSkinIsItsInfluencesWithInverseBindMatricesFromTheSkeleton)
{
    LegScene scene = makeLegScene();
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "leg");
    ASSERT_TRUE(read) << read.error;
    const RiggedSkin& skin = read.model->skins.at(0);
    // Hip, Ankle, Knee in the influence map's (name) order, then the skeleton for the vertex no bone weighs.
    EXPECT_EQ(skin.joints, (std::vector<int>{4, 2, 3, 1}));
    // Each bone is bound in the rest pose: its inverse bind matrix takes a vertex of the geometry (0.3 to the left of
    // the skeleton's origin) into the bone's space: the knee is 1 below the hip, the ankle 2.
    const glm::dvec4 vertex(-0.45, 0.0, -1.0, 1.0);
    EXPECT_NEAR(glm::length(glm::dvec3(skin.inverseBindMatrices[1] * vertex) - glm::dvec3(-0.15, 0.0, -1.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(skin.inverseBindMatrices[2] * vertex) - glm::dvec3(-0.15, 0.0, 0.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(skin.inverseBindMatrices[0] * vertex) - glm::dvec3(-0.15, 0.0, 1.0)), 0.0, 1e-6);
    EXPECT_NEAR(glm::length(glm::dvec3(skin.inverseBindMatrices[3] * vertex) - glm::dvec3(-0.15, 0.0, -1.0)), 0.0, 1e-6);
    const RiggedPrimitive& leg = read.model->meshes[1].primitives[0];
    ASSERT_EQ(leg.getNumVertices(), 19u);
    EXPECT_EQ(leg.indices.size(), 16u * 3u); // the strip of 18 vertices as 16 triangles
    ASSERT_EQ(leg.influencesPerVertex, 4u);
    // Vertex 4 (second row from the hip, left): hip 0.8 + 0.1 and knee 0.2 + 0.1, the weights listed twice added.
    EXPECT_EQ(leg.joints[16], 1u);
    EXPECT_FLOAT_EQ(leg.weights[16], 0.9f);
    EXPECT_EQ(leg.joints[17], 2u);
    EXPECT_FLOAT_EQ(leg.weights[17], 0.3f);
    // Vertex 18: no bone; it stays with the skeleton.
    EXPECT_EQ(leg.joints[18 * 4], 3u);
    EXPECT_FLOAT_EQ(leg.weights[18 * 4], 1.0f);
}

TEST(OsgAnimationImport, TheLegsMaterialsAreItsStateSets)
{
    LegScene scene = makeLegScene();
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "leg");
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    const RiggedMaterial& foot = model.materials.at(model.meshes[0].primitives[0].material);
    EXPECT_FALSE(foot.doubleSided); // face culling on
    EXPECT_EQ(foot.baseColorTexture.image, -1);
    const RiggedMaterial& leg = model.materials.at(model.meshes[1].primitives[0].material);
    EXPECT_EQ(leg.name, "Skin");
    EXPECT_TRUE(leg.doubleSided); // OSG draws both faces unless told otherwise
    EXPECT_EQ(leg.baseColorFactor, glm::dvec4(0.8f, 0.5f, 0.4f, 1.0f));
    ASSERT_GE(leg.baseColorTexture.image, 0);
    EXPECT_EQ(leg.baseColorTexture.wrapS, TextureWrap::ClampToEdge);
    EXPECT_EQ(leg.baseColorTexture.wrapT, TextureWrap::Repeat);
    const RiggedImage& image = model.images.at(leg.baseColorTexture.image);
    EXPECT_EQ(image.width, 2u);
    EXPECT_EQ(image.height, 2u);
    EXPECT_EQ(image.rgba, (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128}));
}

TEST(OsgAnimationImport, TheLegsAnimationsBecomeChannelsOfTheNodesTheyMove)
{
    LegScene scene = makeLegScene();
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "leg");
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    ASSERT_EQ(model.animations.size(), 2u);
    EXPECT_EQ(model.animations[0].name, "Walk");
    EXPECT_EQ(model.animations[1].name, "Kick");
    // Kick: the hip's step translation stays a step. osgAnimation's steps change just after an inner key (at 0.4 s it
    // still shows the first key) and just before the last: the channel holds each value on the same side, keyed one
    // unit in the last place beside those keys. The hip's scale channel holds the rest scale: no channel at all.
    const RiggedAnimation& kick = model.animations[1];
    bool hipSteps = false;
    for (const AnimationChannel& channel : kick.channels)
    {
        EXPECT_FALSE(channel.path == AnimationPath::Scale);
        if (channel.node == 2 && channel.path == AnimationPath::Translation)
        {
            hipSteps = true;
            EXPECT_EQ(channel.interpolation, KeyInterpolation::Step);
            const double inf = std::numeric_limits<double>::infinity();
            EXPECT_EQ(channel.times, (std::vector<double>{0.0, 0.4, std::nextafter(0.4, inf), std::nextafter(0.8, -inf), 0.8}));
            ASSERT_EQ(channel.values.size(), 5u);
            const double y[5] = {0.0, 0.0, 0.1, 0.1, 0.1};
            const double z[5] = {0.0, 0.0, 0.0, 0.0, 0.05};
            for (int k = 0; k < 5; ++k)
            {
                EXPECT_NEAR(channel.values[k].y, y[k], 1e-7) << k;
                EXPECT_NEAR(channel.values[k].z, z[k], 1e-7) << k;
            }
        }
    }
    EXPECT_TRUE(hipSteps);
}

// --- osgAnimation's own motion ---

TEST(OsgAnimationImport, TheLegMovesAsOsgAnimationMovesIt)
{
    for (unsigned a = 0; a < 2; ++a)
    {
        osg::ref_ptr<osg::Node> scene = readScene(legFile());
        ASSERT_TRUE(scene);
        expectLikeOsgAnimation(std::string("leg.osgt ") + (a == 0 ? "Walk" : "Kick"), measureAgainstOsgAnimation(*scene, a));
    }
}

TEST(OsgAnimationImport, OsgsColladaCharactersMoveAsOsgAnimationMovesThem)
{
    osg::ref_ptr<osg::Node> box = readScene(assimpModels("Collada/box_nested_animation.dae"));
    ASSERT_TRUE(box);
    expectLikeOsgAnimation("box_nested_animation.dae through osgdb_dae", measureAgainstOsgAnimation(*box, 0));
    osg::ref_ptr<osg::Node> clips = readScene(assimpModels("Collada/library_animation_clips.dae"));
    ASSERT_TRUE(clips);
    expectLikeOsgAnimation("library_animation_clips.dae through osgdb_dae, clip 1", measureAgainstOsgAnimation(*clips, 1));
}

TEST(OsgAnimationImport, BetweenMatrixKeysTheJointsAreWhereOsgAnimationsBlendedMatricesPutThem)
{
    // The first clip of library_animation_clips.dae turns its bones fast between keys, all in matrix channels.
    // osgdb_dae makes them osgAnimation MatrixLinearChannels, which blend the keys element by element:
    // M(u) = (1 - u) M0 + u M1 = R(u) P(u), a rotation times a stretch that shortens what lies below. The import
    // turns each bone by R(u) and gives the joints below translation channels that put them where osgAnimation's
    // blended matrices put them (docs/import.md), so the thresholds hold against osgAnimation's own playback.
    osg::ref_ptr<osg::Node> scene = readScene(assimpModels("Collada/library_animation_clips.dae"));
    ASSERT_TRUE(scene);
    expectLikeOsgAnimation("library_animation_clips.dae through osgdb_dae, clip 0", measureAgainstOsgAnimation(*scene, 0));
    // The reference can tell: osgAnimation's pose with every transform made rigid (translation and the polar
    // rotation of OSG's decompose, the stretch left out), what a rigid import plays, is the same at the keys and
    // farther than the 1e-3 threshold between them, within what the chords explain.
    scene = readScene(assimpModels("Collada/library_animation_clips.dae"));
    const Fidelity rigid = measureAgainstOsgAnimation(*scene, 0, true).fidelity;
    ASSERT_GT(rigid.comparisons, 0u);
    EXPECT_LE(rigid.atKeys, 1e-5 * rigid.height);
    EXPECT_GT(rigid.betweenKeys, 1e-3 * rigid.height);
    const double bound = matrixChordBound(*OsgAnimationPlayback(*scene, 0).animation, rigid.height);
    EXPECT_LE(rigid.betweenKeys, bound);
    std::cout << "library_animation_clips.dae through osgdb_dae, clip 0: osgAnimation's rigid pose is "
              << rigid.betweenKeys / rigid.height << " of the height off the import between keys (the chords explain up to "
              << bound / rigid.height << ")\n";
}

TEST(OsgAnimationImport, OnlyTheNodesBelowAMatrixChannelGainTranslations)
{
    // The leg with a toe bone 0.3 in front of the ankle: Walk drives the ankle with a matrix channel (blended) and
    // the hip and knee with quaternion and rotate-axis channels (rigid). The toe gains a translation channel, which
    // follows osgAnimation's shrink; the knee (below rigid channels only) and the foot (at the ankle's origin) do not.
    LegScene scene = makeLegScene();
    osg::ref_ptr<osgAnimation::Bone> toe = makeBone("Toe", {new osgAnimation::StackedTranslateElement("translate", osg::Vec3(0, 0.3f, 0))});
    scene.ankle->addChild(toe.get());
    const RiggedModelRead read = convertOsgAnimationScene(*scene.root, "leg");
    ASSERT_TRUE(read) << read.error;
    const RiggedModel& model = *read.model;
    std::vector<std::string> translated;
    for (const AnimationChannel& channel : model.animations[0].channels)
        if (channel.path == AnimationPath::Translation) translated.push_back(model.nodes[channel.node].name);
    std::sort(translated.begin(), translated.end());
    EXPECT_EQ(translated, (std::vector<std::string>{"Rig", "Toe"})); // Rig: its own translate channel
    for (const AnimationChannel& channel : model.animations[1].channels) // Kick: no matrix channel, nothing added
        EXPECT_FALSE(channel.path == AnimationPath::Translation && model.nodes[channel.node].name != "Hip")
            << model.nodes[channel.node].name;
    expectLikeOsgAnimation("leg with a toe, Walk", measureAgainstOsgAnimation(*scene.root, 0));
}

// --- files ---

TEST(OsgAnimationImport, TheCommittedLegFileIsTheFixtureAsOsgWritesIt)
{
    // OSGACTOR_WRITE_FIXTURES=1 rewrites the committed file from OsgAnimationFixture.
    const std::string fresh = std::getenv("OSGACTOR_WRITE_FIXTURES") ? legFile() : written("leg.osgt");
    LegScene scene = makeLegScene();
    ASSERT_TRUE(osgDB::writeNodeFile(*scene.root, fresh));
    EXPECT_EQ(readText(fresh), readText(legFile()))
        << "tests/import/data/osganimation/leg.osgt is not what OsgAnimationFixture makes: run the test with "
           "OSGACTOR_WRITE_FIXTURES=1 and commit the file";
}

TEST(OsgAnimationImport, ReadRiggedModelFileReadsOsgtFilesAsOsgAnimationScenes)
{
    EXPECT_TRUE(isRiggedModelFile("hero.osgt"));
    EXPECT_TRUE(isRiggedModelFile("hero.OSGB"));
    const RiggedModelRead read = readRiggedModelFile(legFile());
    ASSERT_TRUE(read) << read.error;
    EXPECT_EQ(read.model->animations.size(), 2u);
    EXPECT_EQ(read.model->skins.size(), 1u);
}
