// Skinned instancing (InstancedActorGroup, issue 28): on OSMesa, clones of one skinned actor in different poses drawn
// with one instanced draw of their shared SkinnedMesh, against the same crowd drawn ordinarily, each mesh by itself
// on the GPU path. Drawn with the same arithmetic (the skinning program's SkinInstancing::OneAtATime variant on the
// ordinary path) the images are the same bytes: the same instances culled, the same palettes, the same model-view
// matrices. Against the ordinary program (OpenGL's model-view-projection and normal matrices) they differ within a
// bound. Actors whose meshes cannot be drawn instanced are drawn ordinarily, in the same image.
#include "ImageCompare.h"
#include "SkinDrawTestUtil"
#include "TestFigure.h"

#include <osgActor/InstancedActorGroup>
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>
#include <osgActor/core/ClipPlayer>

#include <osg/GL>
#include <osg/GLDefines>
#include <osg/Geode>
#include <osg/Material>
#include <osg/Texture2D>

#include <osg/MatrixTransform>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const osg::Vec4 kBackground(0.55f, 0.65f, 0.8f, 1.0f);
constexpr unsigned kClones = 8;

/** 320 x 200 pixels of sky, or a failed test. */
osg::ref_ptr<OffscreenRenderer> makeRenderer()
{
    std::string error;
    osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(320, 200, error);
    EXPECT_TRUE(renderer) << error;
    if (renderer) renderer->setBackground(kBackground);
    return renderer;
}

class InstancedSkinnedImages : public ::testing::Test
{
protected:
    void SetUp() override
    {
        renderer = makeRenderer();
        ASSERT_TRUE(renderer);
        group = new InstancedActorGroup;
        group->setNumThreads(1);
        // Eight clones of a chain of 8 joints wrapped in a tube (they share its geode and SkinnedMesh), each in a pose
        // of its own, in two rows; the last one stands behind the camera.
        prototype = makeChainActor(8);
        osg::ref_ptr<osg::Material> material = new osg::Material;
        material->setDiffuse(osg::Material::FRONT_AND_BACK, osg::Vec4(0.9f, 0.5f, 0.3f, 1.0f));
        material->setAmbient(osg::Material::FRONT_AND_BACK, osg::Vec4(0.3f, 0.15f, 0.1f, 1.0f));
        prototype.mesh->getOrCreateStateSet()->setAttributeAndModes(material.get());
        for (unsigned a = 0; a < kClones; ++a)
        {
            osg::ref_ptr<ActorNode> actor = osg::clone(prototype.actor.get(), osg::CopyOp::SHALLOW_COPY);
            const bool behind = a == kClones - 1;
            actor->setPreTranslation(osg::Vec3d(0.25 * (a % 4) - 0.45, behind ? -3.0 : 0.3 * (a / 4), 0.0));
            poseSynthetic(*actor, 0.9 * a);
            actors.push_back(actor);
            group->addChild(actor.get());
        }
        renderer->setScene(group.get());
        renderer->setViewMatrixAsLookAt(osg::Vec3d(0.0, -1.6, 0.9), osg::Vec3d(0.0, 0.15, 0.0),
                                        osg::Vec3d(0.0, 0.0, 1.0));
    }

    osg::ref_ptr<osg::Image> renderWith(InstancedActorGroup::DrawMode mode)
    {
        group->setDrawMode(mode);
        return renderer->renderFrame(0.0);
    }

    /** The ordinary path drawn with the instanced draws' arithmetic: the mesh's program variant OneAtATime, put over
      * the one the mesh pushes by the state set of its geode (which the clones share). */
    osg::ref_ptr<osg::Image> renderOrdinaryWithTheSameArithmetic()
    {
        SkinningProgramKey key = prototype.mesh->getProgramKey(profile);
        key.instancing = SkinInstancing::OneAtATime;
        osg::StateSet* geodeState = prototype.mesh->getParent(0)->getOrCreateStateSet();
        geodeState->setAttribute(createSkinningProgram(key).get(), osg::StateAttribute::OVERRIDE);
        osg::ref_ptr<osg::Image> image = renderWith(InstancedActorGroup::ORDINARY);
        geodeState->removeAttribute(osg::StateAttribute::PROGRAM);
        return image;
    }

    /** The instanced image is the bytes of the ordinary path drawn with the same arithmetic; minShare: the least share
      * of the image the crowd covers. */
    void expectTheSameBytes(double minShare = 0.02)
    {
        const osg::ref_ptr<osg::Image> ordinary = renderOrdinaryWithTheSameArithmetic();
        const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
        // The test can fail: the crowd covers part of the image.
        EXPECT_TRUE(isTheSameBytesCovering(*instanced, *ordinary, kBackground, minShare));
    }

    /** The last cull found the last clone out of view (it stands behind the camera) and took the seven others
      * instanced, with one instanced draw of their shared mesh. */
    void expectEveryCloneInOneDraw()
    {
        const InstancedActorGroup::Statistics statistics = group->getStatistics();
        EXPECT_EQ(statistics.actorsInstanced, kClones - 1);
        EXPECT_EQ(statistics.actorsOutOfView, 1u);
        EXPECT_EQ(statistics.actorsOrdinary, 0u);
        EXPECT_EQ(statistics.skinnedDraws, 1u);
        EXPECT_EQ(statistics.skinnedInstances, kClones - 1);
    }

    osg::ref_ptr<OffscreenRenderer> renderer;
    osg::ref_ptr<InstancedActorGroup> group;
    /** The profile of the renderer's state, whose program the ordinary path is drawn with alike. */
    SkinningProfile profile = SkinningProfile::Compatibility;
    SyntheticActor prototype;
    std::vector<osg::ref_ptr<ActorNode>> actors;
};

} // namespace

TEST_F(InstancedSkinnedImages, AnActorSkinnedOnTheCpuIsDrawnOrdinarilyAndTheOthersInstanced)
{
    setSkinningPath(*actors[1], SkinnedMesh::CPU_SKINNING);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.actorsOrdinary, 1u);
    EXPECT_EQ(statistics.actorsInstanced, kClones - 2);
    EXPECT_EQ(statistics.actorsOutOfView, 1u); // the one behind the camera
    EXPECT_EQ(statistics.skinnedDraws, 1u);
    EXPECT_EQ(statistics.skinnedInstances, kClones - 2);
    // The CPU-skinned actor is drawn: hidden, pixels change.
    actors[1]->setNodeMask(0u);
    const osg::ref_ptr<osg::Image> without = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_GT(compareImages(*instanced, *without, 8).numOverTolerance, 100u);
    // And the image is the ordinary path's within the programs' arithmetic (the CPU path is the same on both).
    actors[1]->setNodeMask(~0u);
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    EXPECT_LE(compareImages(*instanced, *ordinary, 2).getShareOverTolerance(), 0.001);
}

TEST_F(InstancedSkinnedImages, AMeshUnderATransformIsDrawnByItselfTheActorInstanced)
{
    // Actor 1's mesh (in its geode) under a transform of its own: the transform is a subtree for the visitor, which
    // draws the mesh by its own cull, one at a time; the actor stays on the instanced path, its mesh not instanced.
    osg::Node* meshGeode = prototype.mesh->getParent(0);
    osg::ref_ptr<osg::MatrixTransform> carrier = new osg::MatrixTransform;
    ASSERT_TRUE(actors[1]->replaceChild(meshGeode, carrier.get()));
    carrier->addChild(meshGeode);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.actorsOrdinary, 0u);
    EXPECT_EQ(statistics.actorsInstanced, kClones - 1);
    EXPECT_EQ(statistics.skinnedDraws, 1u);
    EXPECT_EQ(statistics.skinnedInstances, kClones - 2);
    // The mesh is drawn: hidden, pixels change.
    carrier->setNodeMask(0u);
    const osg::ref_ptr<osg::Image> without = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_GT(compareImages(*instanced, *without, 8).numOverTolerance, 100u);
    // And the image is the ordinary path's within the programs' arithmetic.
    carrier->setNodeMask(~0u);
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    EXPECT_LE(compareImages(*instanced, *ordinary, 2).getShareOverTolerance(), 0.001);
}

TEST_F(InstancedSkinnedImages, AMeshOfItsOwnRenderBinTakesEveryActorWearingItOffTheInstancedPath)
{
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, kClones - 1); // the last is behind the camera
    // A render bin of its own (a transparent mesh sorted by depth): the instances of one draw cannot be sorted.
    prototype.mesh->getStateSet()->setRenderingHint(osg::StateSet::TRANSPARENT_BIN);
    const osg::ref_ptr<osg::Image> image = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 0u);
    EXPECT_EQ(group->getStatistics().actorsOrdinary, kClones - 1);
    EXPECT_EQ(group->getStatistics().skinnedDraws, 0u);
    EXPECT_GT(countDrawnPixels(*image, kBackground), 500u); // drawn ordinarily
    prototype.mesh->getStateSet()->setRenderingHint(osg::StateSet::DEFAULT_BIN);
    prototype.mesh->getStateSet()->setRenderBinToInherit();
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, kClones - 1);
}

TEST_F(InstancedSkinnedImages, ClonesOfADualQuaternionSkinAreTheSameBytesAsTheOrdinaryDualQuaternionPathDrawnAlike)
{
    // Dual-quaternion chains whose mesh is authored at a third of the model's scale (the skin's bind scale 3, which
    // the program reads per draw), worn by the eight clones in poses of their own in place of the linear-blend ones.
    SyntheticActor dual = makeChainActor(8, SkinningMethod::DualQuaternion, 3.0);
    ASSERT_TRUE(dual.skin);
    ASSERT_DOUBLE_EQ(dual.skin->getBindScale(), 3.0);
    ASSERT_EQ(dual.mesh->getProgramKey(SkinningProfile::Compatibility).method, SkinningMethod::DualQuaternion);
    dual.mesh->setStateSet(prototype.mesh->getStateSet());
    for (unsigned a = 0; a < kClones; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(dual.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(actors[a]->getPreTranslation());
        poseSynthetic(*actor, 0.9 * a);
        group->setChild(a, actor.get());
        actors[a] = actor;
    }
    prototype = dual;
    expectTheSameBytes();
    expectEveryCloneInOneDraw();
    // And within the arithmetic's rounding of the ordinary dual-quaternion program.
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_LE(compareImages(*instanced, *ordinary, 2).getShareOverTolerance(), 0.001);
}

TEST_F(InstancedSkinnedImages, DualQuaternionAndLinearBlendClonesAreDrawnInstancedSideBySide)
{
    // Three dual-quaternion clones beside the linear-blend ones: two meshes, two instanced draws, each with its own
    // program variant (and bind scale).
    SyntheticActor dual = makeChainActor(8, SkinningMethod::DualQuaternion, 0.5);
    dual.mesh->setStateSet(prototype.mesh->getStateSet());
    for (unsigned a = 0; a < 3; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(dual.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.25 * a - 0.45, 0.6, 0.0));
        poseSynthetic(*actor, 2.0 + a);
        group->addChild(actor.get());
    }
    // The ordinary path with the instanced arithmetic for both meshes, each overriding its own geode's program.
    const auto overrideProgram = [](SkinnedMesh& mesh) {
        SkinningProgramKey key = mesh.getProgramKey(SkinningProfile::Compatibility);
        key.instancing = SkinInstancing::OneAtATime;
        mesh.getParent(0)->getOrCreateStateSet()->setAttribute(createSkinningProgram(key).get(),
                                                               osg::StateAttribute::OVERRIDE);
    };
    overrideProgram(*prototype.mesh);
    overrideProgram(*dual.mesh);
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    prototype.mesh->getParent(0)->getStateSet()->removeAttribute(osg::StateAttribute::PROGRAM);
    dual.mesh->getParent(0)->getStateSet()->removeAttribute(osg::StateAttribute::PROGRAM);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, kClones - 1 + 3);
    EXPECT_EQ(group->getStatistics().skinnedDraws, 2u);
    EXPECT_EQ(group->getStatistics().skinnedInstances, kClones - 1 + 3);
    EXPECT_TRUE(isTheSameBytesCovering(*instanced, *ordinary, kBackground, 0.03));
}

TEST_F(InstancedSkinnedImages, ClonesInDifferentPosesAreTheSameBytesAsTheOrdinaryPathDrawnWithTheSameArithmetic)
{
    expectTheSameBytes();
    expectEveryCloneInOneDraw();
    EXPECT_EQ(group->getStatistics().draws, 0u);
}

TEST_F(InstancedSkinnedImages, APaletteInATextureBufferOnTheOrdinaryPathGivesTheSameBytesToo)
{
    // The ordinary path's palette in a texture buffer rather than uniforms: the instanced one is in the instances'
    // buffer either way.
    prototype.mesh->setPaletteStorage(SkinPaletteStorage::TextureBuffer);
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().skinnedInstances, kClones - 1);
}

TEST_F(InstancedSkinnedImages, ASkinOfEightInfluencesIsInstancedWithTheSameBytes)
{
    // Random vertices each following 8 random joints of a random tree of 20 (two joints per index component): a
    // mesh of its own, worn by three clones in poses of their own in place of the chains.
    SyntheticActor random = makeRandomActor(20, 600, 8, 5u);
    ASSERT_EQ(random.mesh->getProgramKey(SkinningProfile::Compatibility).influences, 8u);
    group->removeChildren(0, group->getNumChildren());
    for (unsigned a = 0; a < 3; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(random.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.3 * a - 0.3, 0.0, 0.0));
        poseSynthetic(*actor, 1.1 * a);
        group->addChild(actor.get());
    }
    // Its own material, as a model's meshes have (see the class comment of InstancedActorGroup on colour material).
    random.mesh->setStateSet(prototype.mesh->getStateSet());
    prototype = random;
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().skinnedDraws, 1u);
    EXPECT_EQ(group->getStatistics().skinnedInstances, 3u);
}

TEST_F(InstancedSkinnedImages, InstancedClonesAreTheOrdinaryProgramsImageWithinTheArithmeticsRounding)
{
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    // The ordinary program projects with OpenGL's model-view-projection product and turns normals by its normal
    // matrix; the instanced one projects its eye position and turns normals by the model-view matrix's linear part:
    // a few pixels a level apart, a few edge pixels covered or not.
    const ImageComparison difference = compareImages(*instanced, *ordinary, 2);
    ASSERT_TRUE(difference.comparable);
    EXPECT_LE(difference.getShareOverTolerance(), 0.001) << difference.numOverTolerance << " pixels over 2 levels";
    EXPECT_GT(difference.psnr, 40.0);
    EXPECT_GT(countDrawnPixels(*instanced, kBackground), 0.02 * instanced->s() * instanced->t());
}

TEST_F(InstancedSkinnedImages, PosesChangedBetweenFramesShowInTheInstancedImageFrameAfterFrame)
{
    // The instances' buffers come from a pool, one per frame in flight: later frames reuse them, with new palettes.
    const osg::ref_ptr<osg::Image> before = renderWith(InstancedActorGroup::INSTANCED);
    for (int frame = 0; frame < 3; ++frame)
        EXPECT_EQ(compareImages(*renderWith(InstancedActorGroup::INSTANCED), *before, 0).numOverTolerance, 0u);
    poseSynthetic(*actors[2], 4.0);
    poseSynthetic(*actors[5], 7.0);
    const osg::ref_ptr<osg::Image> after = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_GT(compareImages(*after, *before, 8).numOverTolerance, 100u);
    expectTheSameBytes();
}

TEST_F(InstancedSkinnedImages, ActorsOutOfViewAndMaskedMeshesAddNoInstance)
{
    // Every clone but one moved far to the side.
    for (unsigned a = 0; a < kClones; ++a)
        if (a != 3) actors[a]->setPreTranslation(osg::Vec3d(50.0 + a, 0.0, 0.0));
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().skinnedInstances, 1u);
    // The mesh masked out (the traversal mask of the viewer's camera is ~0 but for bits a node mask of 0 lacks).
    prototype.mesh->setNodeMask(0u);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().skinnedInstances, 0u);
    EXPECT_EQ(group->getStatistics().skinnedDraws, 0u);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 1u); // clone 3, the one in view
    EXPECT_EQ(group->getStatistics().actorsOutOfView, kClones - 1);
}

TEST_F(InstancedSkinnedImages, RigidPartsAndSkinnedMeshesOfOneActorShareTheFramesBuffer)
{
    // A ball on one joint of every clone (the clones share it): a rigid instanced draw beside the skinned one, their
    // data one after the other in one texture buffer.
    prototype.actor->getSkeletonNode("j4")->addChild(makeJointBall(0.03f));
    group->removeChildren(0, group->getNumChildren());
    actors.clear();
    for (unsigned a = 0; a < 4; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.25 * a - 0.45, 0.0, 0.0));
        poseSynthetic(*actor, 1.3 * a);
        actors.push_back(actor);
        group->addChild(actor.get());
    }
    group->getOrCreateStateSet()->setAttributeAndModes(InstancedActorGroup::createRigidProgram(false).get());
    expectTheSameBytes(0.01);
    EXPECT_EQ(group->getStatistics().draws, 1u);
    EXPECT_EQ(group->getStatistics().instances, 4u);
    EXPECT_EQ(group->getStatistics().skinnedDraws, 1u);
    EXPECT_EQ(group->getStatistics().skinnedInstances, 4u);
}

TEST(InstancedSkinnedCesiumMen, TexturedMenWalkingAtTheirOwnPacesAreTheSameBytesAsTheOrdinaryPathDrawnAlike)
{
    // Five clones of Cesium Man (one textured SkinnedMesh, 19 joints), each playing the walk at its own speed: at
    // 0.5 s each is in a pose of its own.
    const RiggedModelActor read = readCesiumMan();
    ASSERT_TRUE(read.actor);
    osg::ref_ptr<InstancedActorGroup> group = new InstancedActorGroup;
    group->setNumThreads(1);
    for (unsigned a = 0; a < 5; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(read.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.8 * a - 1.6, 0.5 * (a % 2), 0.0));
        for (const ControllerPtr& controller : actor->getControllers())
            if (ClipPlayer* player = dynamic_cast<ClipPlayer*>(controller.get())) player->setSpeed(0.5 + 0.4 * a);
        group->addChild(actor.get());
    }
    // The file's root scale, a transform above the actor where it has one, goes above the group.
    osg::ref_ptr<osg::Group> scene = group;
    if (read.sceneNode != read.actor)
    {
        scene = static_cast<osg::Group*>(read.sceneNode->clone(osg::CopyOp::SHALLOW_COPY));
        scene->removeChildren(0, scene->getNumChildren());
        scene->addChild(group.get());
    }
    osg::ref_ptr<OffscreenRenderer> renderer = makeRenderer();
    ASSERT_TRUE(renderer);
    renderer->setScene(scene.get());
    renderer->stepTo(0.5, 30.0);
    renderer->frameScene();
    // The ordinary path with the instanced arithmetic, put over the mesh's program by its geode's state set.
    SkinningProgramKey key = read.skinnedMeshes[0]->getProgramKey(SkinningProfile::Compatibility);
    key.instancing = SkinInstancing::OneAtATime;
    osg::StateSet* skinsState = read.skinnedMeshes[0]->getParent(0)->getOrCreateStateSet();
    skinsState->setAttribute(createSkinningProgram(key).get(), osg::StateAttribute::OVERRIDE);
    group->setDrawMode(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> ordinary = renderer->draw();
    skinsState->removeAttribute(osg::StateAttribute::PROGRAM);
    group->setDrawMode(InstancedActorGroup::INSTANCED);
    const osg::ref_ptr<osg::Image> instanced = renderer->draw();
    EXPECT_EQ(group->getStatistics().skinnedDraws, 1u);
    EXPECT_EQ(group->getStatistics().skinnedInstances, 5u);
    EXPECT_TRUE(isTheSameBytesCovering(*instanced, *ordinary, kBackground, 0.05));
    // And the men are in poses of their own: the first and the last differ in some DOF by more than 0.1 rad.
    const ActorNode& first = static_cast<const ActorNode&>(*group->getChild(0));
    const ActorNode& last = static_cast<const ActorNode&>(*group->getChild(4));
    double largest = 0.0;
    for (unsigned d = 0; d < first.getNumDofs(); ++d)
        largest = std::max(largest, std::abs(first.getDof(d) - last.getDof(d)));
    EXPECT_GT(largest, 0.1);
}

TEST_F(InstancedSkinnedImages, ACrowdGrownSinceTheLastCullOverflowsItsRegionsAndIsStillTheSameBytes)
{
    // Each batch's region in the frame's buffer is as large as its data of the cull before: one clone in view, then
    // seven, so that the rigid batch (a ball on a joint of every clone) and the skinned one both overflow and are
    // moved past the regions.
    prototype.actor->getSkeletonNode("j4")->addChild(makeJointBall(0.03f));
    group->getOrCreateStateSet()->setAttributeAndModes(InstancedActorGroup::createRigidProgram(false).get());
    std::vector<osg::Vec3d> places;
    for (unsigned a = 0; a < kClones; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.actor.get(), osg::CopyOp::SHALLOW_COPY);
        places.push_back(actors[a]->getPreTranslation());
        actor->setPreTranslation(a == 3 ? places[a] : osg::Vec3d(50.0 + a, 0.0, 0.0));
        poseSynthetic(*actor, 0.9 * a);
        group->setChild(a, actor.get());
        actors[a] = actor;
    }
    renderWith(InstancedActorGroup::INSTANCED);
    ASSERT_EQ(group->getStatistics().skinnedInstances, 1u);
    ASSERT_EQ(group->getStatistics().instances, 1u);
    for (unsigned a = 0; a < kClones; ++a) actors[a]->setPreTranslation(places[a]);
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().skinnedInstances, kClones - 1);
    EXPECT_EQ(group->getStatistics().instances, kClones - 1);
    // And the frame after, in the regions the grown crowd made.
    expectTheSameBytes();
}

TEST_F(InstancedSkinnedImages, AMeshWhoseOneInstanceIsMoreThanABufferHoldsTakesItsActorsOffTheInstancedPath)
{
    // An instance of the 8-joint chain is its matrix and 8 joints' palette rows, more than 16 texels.
    group->setMaxTexelsPerBuffer(16);
    const osg::ref_ptr<osg::Image> capped = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().texelLimit, 16u);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 0u);
    EXPECT_EQ(group->getStatistics().actorsOrdinary, kClones - 1); // the last is behind the camera
    EXPECT_EQ(group->getStatistics().skinnedDraws, 0u);
    EXPECT_EQ(group->getStatistics().buffers, 0u);
    // Drawn as the ordinary path draws them: the same bytes.
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    EXPECT_TRUE(isTheSameBytesCovering(*capped, *ordinary, kBackground, 0.02));
    // Without the cap they are instanced again.
    group->setMaxTexelsPerBuffer(0);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, kClones - 1);
    EXPECT_EQ(group->getStatistics().buffers, 1u);
}

TEST_F(InstancedSkinnedImages, AFrameWhoseInstancesAreMoreThanABufferHoldsIsDrawnFromSeveralWithTheSameBytes)
{
    // A ball on a joint of every clone beside the skinned mesh: a rigid batch (4 texels an instance) and a skinned
    // one, spread over buffers of 80 texels, so that the skinned instances go two or so to a buffer and a batch's
    // instances are drawn in runs from several buffers, the rigid one filling what the skinned one leaves.
    prototype.actor->getSkeletonNode("j4")->addChild(makeJointBall(0.03f));
    group->removeChildren(0, group->getNumChildren());
    actors.clear();
    for (unsigned a = 0; a < kClones; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.25 * (a % 4) - 0.45, 0.3 * (a / 4), 0.0));
        poseSynthetic(*actor, 0.9 * a);
        actors.push_back(actor);
        group->addChild(actor.get());
    }
    group->getOrCreateStateSet()->setAttributeAndModes(InstancedActorGroup::createRigidProgram(false).get());
    group->setMaxTexelsPerBuffer(80);
    expectTheSameBytes();
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.texelLimit, 80u);
    EXPECT_EQ(statistics.actorsInstanced, kClones);
    EXPECT_EQ(statistics.skinnedInstances, kClones);
    EXPECT_EQ(statistics.instances, kClones);
    // The instances' data is more than one buffer: as many buffers as it takes, and more draws than batches.
    const unsigned skinnedTexels = 4 + 8 * paletteStride(prototype.mesh->getProgramKey(SkinningProfile::Compatibility));
    ASSERT_LE(skinnedTexels, 80u);
    const unsigned perBuffer = 80 / skinnedTexels;
    EXPECT_GE(statistics.buffers, (kClones + perBuffer - 1) / perBuffer);
    EXPECT_GE(statistics.skinnedDraws, statistics.buffers);
    EXPECT_GT(statistics.draws + statistics.skinnedDraws, 2u);
    // And again, from the buffers the first frame made.
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().buffers, statistics.buffers);
}

TEST_F(InstancedSkinnedImages, TheFirstCullTakesOpenGLsLeastBufferAndLaterOnesTheLimitTheDrawAskedTheContextFor)
{
    // Before any draw the cull knows no context: OpenGL's least GL_MAX_TEXTURE_BUFFER_SIZE.
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().texelLimit, 65536u);
    // The draw asked the context: the next cull takes its answer, which the test asks for too.
    renderWith(InstancedActorGroup::INSTANCED);
    osg::GraphicsContext* context = renderer->getCamera()->getGraphicsContext();
    ASSERT_TRUE(context->makeCurrent());
    GLint limit = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &limit);
    ASSERT_GE(limit, 65536);
    EXPECT_EQ(group->getStatistics().texelLimit, static_cast<unsigned>(limit));
    // A cap below it is the limit; above it, the context's.
    group->setMaxTexelsPerBuffer(1000);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().texelLimit, 1000u);
    group->setMaxTexelsPerBuffer(static_cast<unsigned>(limit) + 1u);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().texelLimit, static_cast<unsigned>(limit));
}

TEST_F(InstancedSkinnedImages, InTheCoreProfileClonesAreInstancedWithTheSameBytesAsTheOrdinaryCorePathDrawnAlike)
{
    // OSG's emulation of the core profile: the arrays as generic attributes, the matrices as uniforms. The mesh's
    // programs are its core variants (GLSL 3.30), the instanced one projecting by osg_ProjectionMatrix.
    osg::State* state = renderer->getCamera()->getGraphicsContext()->getState();
    state->setUseVertexAttributeAliasing(true);
    state->setUseModelViewAndProjectionUniforms(true);
    profile = SkinningProfile::Core;
    expectTheSameBytes();
    expectEveryCloneInOneDraw();
    // And within the arithmetic's rounding of the ordinary core program (OSG's model-view-projection uniform).
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_LE(compareImages(*instanced, *ordinary, 2).getShareOverTolerance(), 0.001);
    EXPECT_GT(countDrawnPixels(*instanced, kBackground), 0.02 * instanced->s() * instanced->t());
}

TEST_F(InstancedSkinnedImages, ACrowdOverOpenGLsLeastBufferIsSplitUntilTheContextAnswersAndIsTheSameBytesThroughout)
{
    // 560 clones of a 40-joint chain, each instance 4 + 40 x 3 = 124 texels: 69,440 texels in all, more than the
    // 65,536 of OpenGL's least GL_MAX_TEXTURE_BUFFER_SIZE, which the first instanced cull lays the frame out for.
    SyntheticActor chain = makeChainActor(40);
    chain.mesh->setStateSet(prototype.mesh->getStateSet());
    prototype = chain;
    group->removeChildren(0, group->getNumChildren());
    constexpr unsigned kColumns = 28, kRows = 20;
    for (unsigned a = 0; a < kColumns * kRows; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(chain.actor.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.5 * (a % kColumns) - 9.0, 0.6 * (a / kColumns), 0.0));
        poseSynthetic(*actor, 0.37 * a);
        group->addChild(actor.get());
    }
    renderer->setViewMatrixAsLookAt(osg::Vec3d(0.0, -14.0, 9.0), osg::Vec3d(0.0, 5.0, 0.0), osg::Vec3d(0.0, 0.0, 1.0));
    const unsigned texelsPerInstance =
        4 + 40 * paletteStride(chain.mesh->getProgramKey(SkinningProfile::Compatibility));
    ASSERT_GT(kColumns * kRows * texelsPerInstance, 65536u);
    // The first instanced frame: split over two buffers under OpenGL's minimum.
    expectTheSameBytes(0.05);
    InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.texelLimit, 65536u);
    EXPECT_EQ(statistics.skinnedInstances, kColumns * kRows);
    EXPECT_EQ(statistics.buffers, 2u);
    EXPECT_EQ(statistics.skinnedDraws, 2u);
    // Its draws asked the context (llvmpipe: 2^27 texels): one buffer, one draw from the next frame on.
    expectTheSameBytes(0.05);
    statistics = group->getStatistics();
    EXPECT_GT(statistics.texelLimit, kColumns * kRows * texelsPerInstance);
    EXPECT_EQ(statistics.buffers, 1u);
    EXPECT_EQ(statistics.skinnedDraws, 1u);
}
