// The drawable itself: what it refuses (and then draws nothing, never crashing), the program variant and palette
// storage it picks, the attribute slots it uses, and the palette rows it uploads, against values derived by hand.
#include "SkinDrawTestUtil"

#include <osgActor/core/ActorDefinitionBuilder>

#include <osg/Geode>
#include <osg/Program>
#include <osg/State>
#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <gtest/gtest.h>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** One joint "root" at the origin turning about Z, and a skin of one triangle following it alone. */
struct OneJoint
{
    SkinPtr skin;
    osg::ref_ptr<ActorNode> actor;
};

OneJoint makeOneJoint(const std::string& jointName = "root")
{
    ActorDefinitionBuilder definition("one");
    definition.addJoint("root").dofs(Dof::RZ | Dof::TX | Dof::TY | Dof::TZ);
    SkinBuilder skin("triangle");
    const unsigned joint = skin.addJoint(jointName);
    for (const glm::vec3& p : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
        skin.addInfluence(skin.addVertex(p), joint, 1.0f);
    OneJoint made;
    made.skin = skin.build().skin;
    made.actor = new ActorNode(definition.build().definition);
    return made;
}

osg::ref_ptr<osg::Geometry> triangleSurface(std::vector<unsigned> indices = {0, 1, 2})
{
    osg::ref_ptr<osg::Geometry> surface = new osg::Geometry;
    surface->addPrimitiveSet(new osg::DrawElementsUInt(GL_TRIANGLES, indices.begin(), indices.end()));
    return surface;
}

/** Puts the mesh below the actor in a Geode, runs a frame looking at the origin; what was drawn. */
std::vector<FrameDriver::CulledLeaf> drawOneFrame(ActorNode& actor, SkinnedMesh& mesh)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(&mesh);
    actor.addChild(geode.get());
    FrameDriver driver(&actor);
    driver.lookAt(osg::Vec3d(0, -6, 0), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1), 60.0);
    driver.frame(0.0);
    return driver.culledLeaves();
}

} // namespace

TEST(SkinnedMesh, RefusesASurfaceThatDoesNotFitTheSkinAndDrawsNothing)
{
    const OneJoint one = makeOneJoint();
    osg::ref_ptr<SkinnedMesh> none = new SkinnedMesh;
    EXPECT_EQ(none->getSetupError(), "no skin");
    EXPECT_EQ(osg::ref_ptr<SkinnedMesh>(new SkinnedMesh(one.skin, nullptr))->getSetupError(), "no surface");

    osg::ref_ptr<SkinnedMesh> beyond = new SkinnedMesh(one.skin, triangleSurface({0, 1, 3}).get());
    EXPECT_EQ(beyond->getSetupError(), "primitive set 0 names vertex 3 at position 2; the skin has 3");

    osg::ref_ptr<osg::Geometry> shortCoordinates = triangleSurface();
    shortCoordinates->setTexCoordArray(0, new osg::Vec2Array(2), osg::Array::BIND_PER_VERTEX);
    EXPECT_EQ(osg::ref_ptr<SkinnedMesh>(new SkinnedMesh(one.skin, shortCoordinates.get()))->getSetupError(),
              "the surface's texture coordinates 0 has 2 entries for 3 vertices");

    osg::ref_ptr<osg::Geometry> ownVertices = triangleSurface();
    ownVertices->setVertexArray(new osg::Vec3Array(3));
    EXPECT_EQ(osg::ref_ptr<SkinnedMesh>(new SkinnedMesh(one.skin, ownVertices.get()))->getSetupError(),
              "the surface has its own vertex or normal array; the skin's are drawn");

    osg::ref_ptr<osg::Geometry> unitSix = triangleSurface();
    unitSix->setTexCoordArray(6, new osg::Vec2Array(3), osg::Array::BIND_PER_VERTEX);
    EXPECT_NE(osg::ref_ptr<SkinnedMesh>(new SkinnedMesh(one.skin, unitSix.get()))->getSetupError().find(
                  "units 5-7 alias the joint and weight attributes"),
              std::string::npos);

    // Drawn, picked and bounded without a crash: nothing drawn, nothing hit.
    EXPECT_TRUE(drawOneFrame(*one.actor, *beyond).empty());
    EXPECT_EQ(beyond->getBindPoseGeometry(SkinningProfile::Compatibility), nullptr);
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    EXPECT_FALSE(beyond->computeSkinnedVertices(*one.actor, *positions));
    osg::ref_ptr<osgUtil::LineSegmentIntersector> line =
        new osgUtil::LineSegmentIntersector(osg::Vec3d(0.3, -5, 0.3), osg::Vec3d(0.3, 5, 0.3));
    osgUtil::IntersectionVisitor visitor(line.get());
    one.actor->accept(visitor);
    EXPECT_FALSE(line->containsIntersections());
}

TEST(SkinnedMesh, AnActorLackingAJointOfTheSkinDrawsNothing)
{
    const OneJoint one = makeOneJoint("shoulder"); // the actor's joint is "root"
    osg::ref_ptr<SkinnedMesh> mesh = new SkinnedMesh(one.skin, triangleSurface().get());
    EXPECT_TRUE(mesh->getSetupError().empty());
    EXPECT_TRUE(drawOneFrame(*one.actor, *mesh).empty());
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    EXPECT_FALSE(mesh->computeSkinnedVertices(*one.actor, *positions));
    EXPECT_FALSE(mesh->getSkinnedBound(*one.actor).valid());
}

TEST(SkinnedMesh, AMeshBelowNoActorDrawsNothing)
{
    const OneJoint one = makeOneJoint();
    osg::ref_ptr<SkinnedMesh> mesh = new SkinnedMesh(one.skin, triangleSurface().get());
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(mesh.get());
    FrameDriver driver(geode.get());
    driver.lookAt(osg::Vec3d(0, -6, 0), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1), 60.0);
    driver.frame(0.0);
    EXPECT_TRUE(driver.culledDrawables().empty());
}

TEST(SkinnedMesh, UploadsThePaletteRowsOfTheSkinningMatrix)
{
    // The joint turned 90 degrees about Z by rz and slid by (1, 2, 3), which the joint matrix applies first
    // (skl_m = Rz T, docs/architecture.md); inverse bind the identity, so the skinning matrix is that motion:
    // x -> Rz (x + t) = (-y - 2, x + 1, z + 3). Its rows, in the palette: (0 -1 0 -2), (1 0 0 1), (0 0 1 3).
    const OneJoint one = makeOneJoint();
    one.actor->setDof("root.rz", M_PI / 2);
    one.actor->setDof("root.tx", 1.0);
    one.actor->setDof("root.ty", 2.0);
    one.actor->setDof("root.tz", 3.0);
    osg::ref_ptr<SkinnedMesh> mesh = new SkinnedMesh(one.skin, triangleSurface().get());
    const std::vector<FrameDriver::CulledLeaf> leaves = drawOneFrame(*one.actor, *mesh);
    ASSERT_EQ(leaves.size(), 1u);
    const osg::Uniform* palette = leaves[0].stateSets.back()->getUniform("osgActor_palette");
    ASSERT_TRUE(palette);
    ASSERT_EQ(palette->getNumElements(), 3u);
    const float expected[12] = {0, -1, 0, -2, 1, 0, 0, 1, 0, 0, 1, 3};
    for (unsigned i = 0; i < 12; ++i) EXPECT_NEAR((*palette->getFloatArray())[i], expected[i], 1e-7f) << "entry " << i;
    // The triangle (1,0,0), (0,1,0), (0,0,1) moved to (-2,2,3), (-3,1,3), (-2,1,4): on the CPU, and inside the bound.
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    ASSERT_TRUE(mesh->computeSkinnedVertices(*one.actor, *positions));
    const osg::Vec3 moved[3] = {osg::Vec3(-2, 2, 3), osg::Vec3(-3, 1, 3), osg::Vec3(-2, 1, 4)};
    for (unsigned v = 0; v < 3; ++v)
    {
        EXPECT_LT(((*positions)[v] - moved[v]).length(), 1e-6f) << "vertex " << v;
        EXPECT_TRUE(mesh->getSkinnedBound(*one.actor).contains(moved[v])) << "vertex " << v;
    }
}

TEST(SkinnedMesh, KeepsThePaletteInUniformsWhileItFitsAndInATextureBufferBeyond)
{
    // Linear blend: three rows a joint, kMaxUniformPaletteVectors (216) rows in uniforms, so 72 joints.
    EXPECT_EQ(makeChainActor(72).mesh->getEffectivePaletteStorage(), SkinPaletteStorage::UniformArray);
    EXPECT_EQ(makeChainActor(73).mesh->getEffectivePaletteStorage(), SkinPaletteStorage::TextureBuffer);
    // Dual quaternions: two rows a joint, so 108.
    EXPECT_EQ(makeChainActor(108, SkinningMethod::DualQuaternion).mesh->getEffectivePaletteStorage(),
              SkinPaletteStorage::UniformArray);
    EXPECT_EQ(makeChainActor(109, SkinningMethod::DualQuaternion).mesh->getEffectivePaletteStorage(),
              SkinPaletteStorage::TextureBuffer);
    // Asked for uniforms it cannot hold: the texture buffer still.
    SyntheticActor large = makeChainActor(300);
    large.mesh->setPaletteStorage(SkinPaletteStorage::UniformArray);
    EXPECT_EQ(large.mesh->getEffectivePaletteStorage(), SkinPaletteStorage::TextureBuffer);
    EXPECT_EQ(large.mesh->getProgramKey(SkinningProfile::Core).palette, SkinPaletteStorage::TextureBuffer);
}

TEST(SkinnedMesh, ChoosesTheProgramVariantOfItsSkin)
{
    const SkinningProgramKey dual = makeRandomActor(8, 30, 6, 3u, SkinningMethod::DualQuaternion).mesh->getProgramKey(
        SkinningProfile::Core);
    EXPECT_EQ(dual.profile, SkinningProfile::Core);
    EXPECT_EQ(dual.method, SkinningMethod::DualQuaternion);
    EXPECT_EQ(dual.influences, 8u);
    EXPECT_EQ(paletteStride(dual), 2u);
    const SkinningProgramKey linear = readCesiumMan().skinnedMeshes[0]->getProgramKey(SkinningProfile::Compatibility);
    EXPECT_EQ(linear.method, SkinningMethod::LinearBlend);
    EXPECT_EQ(linear.influences, 4u);
    EXPECT_EQ(paletteStride(linear), linear.inverseTranspose ? 6u : 3u);
    // The GLSL is in the library: no #include, no file; each profile's own version line.
    EXPECT_EQ(skinningShaderSource(linear, osg::Shader::VERTEX).rfind("#version 120\n", 0), 0u);
    SkinningProgramKey core = linear;
    core.profile = SkinningProfile::Core;
    EXPECT_EQ(skinningShaderSource(core, osg::Shader::VERTEX).rfind("#version 330\n", 0), 0u);
    core.palette = SkinPaletteStorage::TextureBuffer;
    core.profile = SkinningProfile::Compatibility;
    EXPECT_EQ(skinningShaderSource(core, osg::Shader::FRAGMENT).rfind("#version 150 compatibility\n", 0), 0u);
    EXPECT_EQ(getSkinningProgramStateSet(core), getSkinningProgramStateSet(core));
}

namespace {

/** The program the GPU path drew Cesium Man with in the driver's last cull. */
const osg::Program* programDrawn(const FrameDriver& driver)
{
    const std::vector<FrameDriver::CulledLeaf> leaves = driver.culledLeaves();
    EXPECT_EQ(leaves.size(), 1u);
    const osg::Program* found = nullptr;
    if (leaves.empty()) return found;
    for (const osg::StateSet* stateSet : leaves[0].stateSets) // outermost first: the last one holding a program wins
        if (const osg::Program* program = dynamic_cast<const osg::Program*>(
                stateSet->getAttribute(osg::StateAttribute::PROGRAM)))
            found = program;
    return found;
}

std::string vertexSourceOf(const osg::Program& program)
{
    for (unsigned i = 0; i < program.getNumShaders(); ++i)
        if (program.getShader(i)->getType() == osg::Shader::VERTEX) return program.getShader(i)->getShaderSource();
    return std::string();
}

} // namespace

TEST(SkinnedMesh, LightsWithTheLightsTheStateTurnsOnAndTakesTheFragmentShadersOfAFragmentOnlyProgram)
{
    const RiggedModelActor read = readCesiumMan(SkinnedMesh::GPU_SKINNING);
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    scene->addChild(read.sceneNode.get());
    FrameDriver driver(scene.get());
    driver.lookAt(osg::Vec3d(0, -5, 0.8), osg::Vec3d(0, 0, 0.8), osg::Vec3d(0, 0, 1));

    // The scene view's headlight alone: light 0.
    driver.frame(0.1);
    const osg::Program* headlit = programDrawn(driver);
    ASSERT_TRUE(headlit);
    EXPECT_NE(vertexSourceOf(*headlit).find("#define OSGACTOR_LIGHTS_ON bool[8](true, false, false"),
              std::string::npos);

    // Light 2 turned on below, light 0 turned off with OVERRIDE above the actor's own state, which turns it back on
    // (not PROTECTED: the override holds), and osgShadow-like fragment shaders over everything.
    osg::StateSet* state = scene->getOrCreateStateSet();
    state->setMode(GL_LIGHT2, osg::StateAttribute::ON);
    state->setMode(GL_LIGHT0, osg::StateAttribute::OFF | osg::StateAttribute::OVERRIDE);
    read.sceneNode->getOrCreateStateSet()->setMode(GL_LIGHT0, osg::StateAttribute::ON);
    state->setTextureMode(1, GL_TEXTURE_GEN_S, osg::StateAttribute::ON);
    osg::ref_ptr<osg::Program> shadowLike = new osg::Program;
    osg::ref_ptr<osg::Shader> fragment =
        new osg::Shader(osg::Shader::FRAGMENT, "void main() { gl_FragColor = gl_Color * gl_TexCoord[1].q; }\n");
    shadowLike->addShader(fragment.get());
    state->setAttribute(shadowLike.get());
    driver.frame(0.2);
    const osg::Program* composed = programDrawn(driver);
    ASSERT_TRUE(composed);
    const std::string source = vertexSourceOf(*composed);
    EXPECT_NE(source.find("#define OSGACTOR_LIGHTS_ON bool[8](false, false, true, false"), std::string::npos);
    EXPECT_NE(source.find("#define OSGACTOR_FIXED_FUNCTION_OUTPUTS 1"), std::string::npos);
    EXPECT_NE(source.find("#define OSGACTOR_EYE_LINEAR_UNITS 2"), std::string::npos);
    ASSERT_EQ(composed->getNumShaders(), 2u);
    EXPECT_TRUE(composed->getShader(0) == fragment.get() || composed->getShader(1) == fragment.get())
        << "the fragment-only program's own shader object";

    // A program with a vertex shader of its own is not composed with: the skinning program replaces it.
    shadowLike->addShader(new osg::Shader(osg::Shader::VERTEX, "void main() { gl_Position = ftransform(); }\n"));
    driver.frame(0.3);
    const osg::Program* own = programDrawn(driver);
    ASSERT_TRUE(own);
    EXPECT_NE(vertexSourceOf(*own).find("#define OSGACTOR_FIXED_FUNCTION_OUTPUTS 0"), std::string::npos);
    EXPECT_NE(own, shadowLike.get());
    // The palette is one for all of these programs: filled once per frame.
    EXPECT_EQ(read.skinnedMeshes[0]->getStatistics(*read.actor).paletteUploads, 3u);
}

TEST(SkinnedMesh, PutsItsInfluencesInSlotsNoArrayOfTheMeshAliases)
{
    const RiggedModelActor read = readCesiumMan();
    SkinnedMesh& mesh = *read.skinnedMeshes[0];
    for (const SkinningProfile profile : {SkinningProfile::Compatibility, SkinningProfile::Core})
    {
        const SkinAttributeSlots slots = skinAttributeSlots(profile);
        const osg::Geometry& geometry = *mesh.getBindPoseGeometry(profile);
        EXPECT_TRUE(geometry.getVertexAttribArray(slots.joints));
        EXPECT_TRUE(geometry.getVertexAttribArray(slots.weights));
        EXPECT_EQ(geometry.getDataVariance(), osg::Object::UNSPECIFIED); // never DYNAMIC
        // The slots OSG's aliasing gives the arrays the mesh has (vertex, normal, colour, texture coordinates 0-4).
        osg::ref_ptr<osg::State> state = new osg::State;
        state->setUseVertexAttributeAliasing(true);
        std::vector<unsigned> aliased{unsigned(state->getVertexAlias()._location),
                                      unsigned(state->getNormalAlias()._location),
                                      unsigned(state->getColorAlias()._location)};
        for (unsigned unit = 0; unit < 5; ++unit) aliased.push_back(state->getTexCoordAliasList()[unit]._location);
        // NVIDIA's conventional aliasing in the compatibility profile.
        const std::vector<unsigned> conventional{0, 2, 3, 4, 5, 8, 9, 10, 11, 12, 13, 14, 15};
        const std::vector<unsigned>& taken = profile == SkinningProfile::Core ? aliased : conventional;
        for (unsigned slot : {slots.joints, slots.weights, slots.weights1})
            EXPECT_EQ(std::count(taken.begin(), taken.end(), slot), 0) << "slot " << slot;
        // And within what OSG 3.6.5's aliasing VertexArrayState holds dispatchers for (0-10).
        if (profile == SkinningProfile::Core)
        {
            for (unsigned slot : {slots.joints, slots.weights, slots.weights1}) EXPECT_LE(slot, 10u);
        }
    }
}

TEST(SkinnedMesh, ASkinOfMoreThan4096JointsWithEightInfluencesIsSkinnedOnTheCpu)
{
    // The GPU path packs two joint indices below 4096 in one float; beyond, the CPU path draws, whatever is asked.
    SyntheticActor large = makeRandomActor(4100, 30, 8, 9u);
    ASSERT_EQ(large.mesh->getProgramKey(SkinningProfile::Compatibility).influences, 8u);
    large.mesh->setSkinningPath(*large.actor, SkinnedMesh::GPU_SKINNING);
    FrameDriver driver(large.actor.get());
    driver.lookAt(osg::Vec3d(0, -6, 0), osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1), 60.0);
    driver.frame(0.0);
    const std::vector<const osg::Drawable*> drawn = driver.culledDrawables();
    ASSERT_EQ(drawn.size(), 1u);
    EXPECT_NE(drawn[0], large.mesh->getBindPoseGeometry(SkinningProfile::Compatibility));
    EXPECT_EQ(large.mesh->getStatistics(*large.actor).cpuSkinnings, 1u);
    EXPECT_EQ(large.mesh->getStatistics(*large.actor).paletteUploads, 0u);
}
