// Many actors of one kind drawn as one (InstancedActorGroup, issue 28): on OSMesa, the instanced crowd against the
// same crowd drawn ordinarily. Drawn with the same shader on both paths the images are the same bytes (the same
// instances culled, at the same model-view matrices); against the ordinary path's fixed-function lighting they differ
// within a bound. Actors that need the ordinary traversal are drawn ordinarily, in the same image.
#include "ImageCompare.h"
#include "TestFigure.h"

#include <osgActor/InstancedActorGroup>
#include <osgActor/SkeletonNode>
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>

#include <osg/Geometry>
#include <osg/Group>
#include <osg/MatrixTransform>
#include <osg/Switch>
#include <osg/Texture2D>
#include <osgDB/ReadFile>

#include <gtest/gtest.h>

#include <vector>


using namespace osgActor;
using namespace osgActor::test;

namespace {

const osg::Vec4 kBackground(0.55f, 0.65f, 0.8f, 1.0f);

/** Pixels that are not the sky. */
unsigned countDrawn(const osg::Image& image) { return countDrawnPixels(image, kBackground); }

class InstancedImages : public ::testing::Test
{
protected:
    void SetUp() override
    {
        std::string error;
        renderer = OffscreenRenderer::create(320, 200, error);
        ASSERT_TRUE(renderer) << error;
        renderer->setBackground(kBackground);
        osg::ref_ptr<osg::Group> scene = new osg::Group;
        scene->addChild(makeFloor(12.0f));
        group = new InstancedActorGroup;
        group->setNumThreads(1);
        scene->addChild(group.get());
        // Nine clones of one figure (they share its geodes), posed apart, in two rows; the last two stand behind the
        // camera. Actor 3 has a hidden arm: instanced but for the arm, which the visitor traverses (and skips).
        prototype = makeTestFigure();
        ASSERT_TRUE(prototype);
        for (unsigned a = 0; a < 9; ++a)
        {
            osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
            const bool behind = a >= 7;
            actor->setPreTranslation(osg::Vec3d(0.9 * a - 2.7, behind ? -9.0 : 0.6 * (a % 3), 0.0));
            poseCrowdMember(*actor, a);
            actors.push_back(actor);
            group->addChild(actor.get());
        }
        actors[3]->getSkeletonNode("l_shoulder")->setHidden(true);
        renderer->setScene(scene.get());
        // Close enough that the figures at both ends are cut by the image's sides.
        renderer->setViewMatrixAsLookAt(osg::Vec3d(0.3, -5.0, 1.6), osg::Vec3d(0.0, 0.0, 0.8),
                                        osg::Vec3d(0.0, 0.0, 1.0));
    }

    osg::ref_ptr<osg::Image> renderWith(InstancedActorGroup::DrawMode mode)
    {
        group->setDrawMode(mode);
        return renderer->renderFrame(0.0);
    }

    /** Both paths drawn with the instanced program's arithmetic: the ordinary path under createRigidProgram(false). */
    void drawOrdinaryPathWithTheSameShader()
    {
        group->getOrCreateStateSet()->setAttributeAndModes(InstancedActorGroup::createRigidProgram(false).get());
    }

    /** minCrowdShare: the least share of the image that is not sky. */
    void expectTheSameBytes(double minCrowdShare = 0.5)
    {
        const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
        const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
        // The test can fail: the crowd and its floor cover part of the image.
        EXPECT_TRUE(isTheSameBytesCovering(*instanced, *ordinary, kBackground, minCrowdShare));
    }

    osg::ref_ptr<OffscreenRenderer> renderer;
    osg::ref_ptr<InstancedActorGroup> group;
    osg::ref_ptr<ActorNode> prototype;
    std::vector<osg::ref_ptr<ActorNode>> actors;
};

/** The drawables below a skeleton node and the nodes below it but hidden ones. */
unsigned numPartsShownBelow(const osg::Group& node)
{
    unsigned parts = 0;
    for (unsigned c = 0; c < node.getNumChildren(); ++c)
    {
        const osg::Node& child = *node.getChild(c);
        if (const osg::Geode* geode = child.asGeode()) parts += geode->getNumDrawables();
        const SkeletonNode* joint = dynamic_cast<const SkeletonNode*>(&child);
        if (joint && !joint->getHidden()) parts += numPartsShownBelow(*joint);
    }
    return parts;
}

/** The parts of a test figure that are drawn: those below no hidden joint. */
unsigned numPartsShown(ActorNode& actor) { return numPartsShownBelow(actor); }

/** The number of drawables below a test figure: one geode of one drawable per part. */
unsigned numParts(ActorNode& actor)
{
    unsigned parts = 0;
    for (unsigned j = 0; j < actor.getNumSkeletonNodes(); ++j)
        for (unsigned c = 0; c < actor.getSkeletonNode(j)->getNumChildren(); ++c)
            if (osg::Geode* geode = actor.getSkeletonNode(j)->getChild(c)->asGeode()) parts += geode->getNumDrawables();
    return parts;
}

/** The geometries of a test figure's parts (its clones share them). */
std::vector<osg::Geometry*> partGeometries(ActorNode& actor)
{
    std::vector<osg::Geometry*> geometries;
    for (unsigned j = 0; j < actor.getNumSkeletonNodes(); ++j)
        for (unsigned c = 0; c < actor.getSkeletonNode(j)->getNumChildren(); ++c)
            if (osg::Geode* geode = actor.getSkeletonNode(j)->getChild(c)->asGeode())
                for (unsigned d = 0; d < geode->getNumDrawables(); ++d)
                    if (osg::Geometry* geometry = geode->getDrawable(d)->asGeometry()) geometries.push_back(geometry);
    return geometries;
}

/** How many of the geometries have the GL buffer object of their vertex array made in the context. */
unsigned countVertexBuffersMade(const std::vector<osg::Geometry*>& geometries, unsigned contextID)
{
    unsigned numMade = 0;
    for (const osg::Geometry* geometry : geometries)
    {
        const osg::BufferObject* buffer = geometry->getVertexArray()->getBufferObject();
        const osg::GLBufferObject* made = buffer ? buffer->getGLBufferObject(contextID) : nullptr;
        if (made && made->getGLObjectID() != 0) ++numMade;
    }
    return numMade;
}

} // namespace

TEST_F(InstancedImages, AGroupWithoutActorsDrawsNothingInstancedAndItsOtherChildrenOrdinarily)
{
    group->removeChildren(0, group->getNumChildren());
    group->addChild(makeJointBall(0.3f));
    const osg::ref_ptr<osg::Image> image = renderWith(InstancedActorGroup::INSTANCED);
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.actorsInstanced, 0u);
    EXPECT_EQ(statistics.actorsOrdinary, 0u);
    EXPECT_EQ(statistics.draws, 0u);
    // The ball (yellow) is drawn.
    const osg::Vec3d centre = renderer->projectToWindow(osg::Vec3d(0.0, 0.0, 0.0));
    const unsigned char* pixel = image->data(static_cast<int>(centre.x()), static_cast<int>(centre.y()));
    EXPECT_GT(pixel[0], pixel[2] + 40);
}

TEST_F(InstancedImages, ActorsThatNeedTheOrdinaryTraversalAreDrawnOrdinarily)
{
    // Each of these takes one actor off the instanced path: a state set on a skeleton node, a cull callback on the
    // actor, a texture on a part, and a subclass's cull mode.
    actors[0]->setCullMode(ActorNode::CULL_NODE_BY_NODE);
    actors[1]->getSkeletonNode("chest")->getOrCreateStateSet();
    osg::ref_ptr<osg::Geode> textured = makeJointBall(0.05f);
    textured->getOrCreateStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D);
    actors[4]->getSkeletonNode("head")->addChild(textured.get());
    actors[6]->setCullCallback(new osg::NodeCallback);
    drawOrdinaryPathWithTheSameShader();
    renderWith(InstancedActorGroup::INSTANCED);
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    // Actors 1 to 5 are in view (the others beyond the image's sides or behind the camera): of them 2, 3 (its hidden
    // arm traversed by the visitor) and 5 are drawn instanced. Actors 0 and 6 are handed to the ordinary traversal
    // whether in view or not; 7 and 8 are found out of view by the instanced cull's first test.
    EXPECT_EQ(statistics.actorsOrdinary, 4u);
    EXPECT_EQ(statistics.actorsInstanced, 3u);
    EXPECT_EQ(statistics.actorsOutOfView, 2u);
    EXPECT_EQ(statistics.instances, 2u * numParts(*prototype) + numPartsShown(*actors[3]));
    EXPECT_EQ(statistics.draws, numParts(*prototype));
    // And the image is the image of the ordinary path.
    actors[4]->getSkeletonNode("head")->removeChild(textured.get()); // a texture that has no image draws black
    expectTheSameBytes();
}

TEST_F(InstancedImages, NodesBelowJointsAreTraversedOrdinarilyTheRestOfTheActorInstanced)
{
    // A prop in a hand (a user's transform holding a box, with a cull callback counting its visits), a switch below
    // a head, a hidden arm (actor 3): the visitor traverses each in its joint's frame, with the actor and its joints
    // on the node path, and the rest of the actor is instanced; the image is the ordinary path's, byte for byte.
    class PathRecorder : public osg::NodeCallback
    {
    public:
        void operator()(osg::Node* node, osg::NodeVisitor* nv) override
        {
            ++calls;
            path = nv->getNodePath();
            traverse(node, nv);
        }
        unsigned calls = 0;
        osg::NodePath path;
    };
    osg::ref_ptr<PathRecorder> recorder = new PathRecorder;
    osg::ref_ptr<osg::MatrixTransform> prop = new osg::MatrixTransform(osg::Matrix::translate(0.0, -0.1, -0.3));
    prop->addChild(makePart(new osg::Box(osg::Vec3(), 0.06f, 0.06f, 0.5f), osg::Vec4(0.5f, 0.5f, 0.55f, 1.0f)));
    prop->setCullCallback(recorder.get());
    actors[2]->getSkeletonNode("r_elbow")->addChild(prop.get());
    // A joint with a cull callback of its own: what hangs below it is drawn one at a time.
    osg::ref_ptr<PathRecorder> jointRecorder = new PathRecorder;
    actors[5]->getSkeletonNode("l_elbow")->setCullCallback(jointRecorder.get());
    osg::ref_ptr<osg::Switch> switched = new osg::Switch;
    // Beside the head, touching nothing instanced (where two surfaces meet at the same depth, which is drawn first
    // decides the pixel, and the instanced draws come in an order of their own).
    const osg::Vec4 green(0.3f, 0.8f, 0.3f, 1.0f);
    switched->addChild(makePart(new osg::Sphere(osg::Vec3(0.25f, 0.0f, 0.1f), 0.06f), green), false);
    actors[4]->getSkeletonNode("head")->addChild(switched.get());
    drawOrdinaryPathWithTheSameShader();
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> withProp = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_TRUE(isTheSameBytesCovering(*withProp, *ordinary, kBackground, 0.5));
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    // Actors 0 to 6 are instanced (0 and 6 cut by the image's sides), 7 and 8 behind the camera; the parts of 1, 2, 4,
    // 5 (but its left forearm's) and the shown ones of 3 in view, the prop and the switch's ball not among them.
    EXPECT_EQ(statistics.actorsInstanced, 7u);
    EXPECT_EQ(statistics.actorsOrdinary, 0u);
    const unsigned forearm = numPartsShownBelow(*actors[5]->getSkeletonNode("l_elbow"));
    EXPECT_EQ(forearm, 2u);
    EXPECT_EQ(statistics.instances, 4u * numParts(*prototype) - forearm + numPartsShown(*actors[3]));
    EXPECT_EQ(recorder->calls, 2u); // once by the ordinary path, once by the instanced one
    EXPECT_EQ(jointRecorder->calls, 2u);
    // The path the ordinary traversal gives the prop's callback, which the instanced cull's last gave it: the group,
    // the actor, the joints from the pelvis down to the elbow, the prop.
    ASSERT_GE(recorder->path.size(), 7u);
    const osg::NodePath tail(recorder->path.end() - 7, recorder->path.end());
    EXPECT_EQ(tail[0], group.get());
    EXPECT_EQ(tail[1], actors[2].get());
    EXPECT_EQ(tail[2], actors[2]->getSkeletonNode("pelvis"));
    EXPECT_EQ(tail[3], actors[2]->getSkeletonNode("chest"));
    EXPECT_EQ(tail[4], actors[2]->getSkeletonNode("r_shoulder"));
    EXPECT_EQ(tail[5], actors[2]->getSkeletonNode("r_elbow"));
    EXPECT_EQ(tail[6], prop.get());
    // Still, before a still camera: the actors' instances and their subtrees' frames are kept, the subtrees traversed
    // again at every cull.
    for (int frame = 0; frame < 3; ++frame)
    {
        const unsigned calls = recorder->calls;
        EXPECT_TRUE(isTheSameBytesCovering(*renderWith(InstancedActorGroup::INSTANCED), *ordinary, kBackground, 0.5));
        EXPECT_EQ(recorder->calls, calls + 1);
    }
    EXPECT_EQ(group->getStatistics().actorsKept, 7u);
    // The switch turned on, and the prop moved with its arm: still the ordinary image.
    switched->setAllChildrenOn();
    actors[2]->setDof("r_shoulder.ry", 1.2);
    expectTheSameBytes();
    // The test can fail: without the prop the image changes where it was.
    const osg::ref_ptr<osg::Image> held = renderWith(InstancedActorGroup::INSTANCED);
    actors[2]->getSkeletonNode("r_elbow")->removeChild(prop.get());
    const ImageComparison change = compareImages(*renderWith(InstancedActorGroup::INSTANCED), *held, 8);
    ASSERT_TRUE(change.comparable);
    EXPECT_GT(change.numOverTolerance, 20u);
}

TEST_F(InstancedImages, ATextureAddedInPlaceToASharedPartsStateTakesEveryActorSharingItOffTheInstancedPath)
{
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 7u); // all but 7 and 8 (behind the camera)
    EXPECT_EQ(group->getStatistics().actorsOutOfView, 2u);
    // The clones share the head's geode and its state set; OSG lets a state set change without telling anyone.
    osg::Node* head = prototype->getSkeletonNode("head")->getChild(0);
    ASSERT_NE(head->getStateSet(), nullptr);
    head->getStateSet()->setTextureAttributeAndModes(0, new osg::Texture2D);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 0u);
    EXPECT_EQ(group->getStatistics().actorsOrdinary, 7u);
    EXPECT_EQ(group->getStatistics().actorsOutOfView, 2u);
    EXPECT_EQ(group->getStatistics().draws, 0u);
}

TEST_F(InstancedImages, InstancedCrowdIsTheSameBytesAsTheOrdinaryPathDrawnWithTheSameShader)
{
    drawOrdinaryPathWithTheSameShader();
    expectTheSameBytes();
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    // Of the nine clones, 7 and 8 stand behind the camera, out of view; the seven others are instanced (3 but for its
    // hidden arm), and of them the parts of 1, 2, 4 and 5 and the shown ones of 3 are in view (0 and 6 are cut by the
    // image's sides, their parts beyond them): one draw per part of the figure.
    EXPECT_EQ(statistics.actorsInstanced, 7u);
    EXPECT_EQ(statistics.actorsOutOfView, 2u);
    EXPECT_EQ(statistics.actorsOrdinary, 0u);
    EXPECT_EQ(statistics.draws, numParts(*prototype));
    EXPECT_EQ(statistics.instances, 4u * numParts(*prototype) + numPartsShown(*actors[3]));
}

TEST_F(InstancedImages, InstancedCrowdIsTheOrdinaryFixedFunctionImageWithinTheShadersRounding)
{
    const osg::ref_ptr<osg::Image> ordinary = renderWith(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> instanced = renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_TRUE(matchesReference(*instanced, "crowd_instanced"));
    // Fixed function turns normals by the inverse transpose OpenGL computes in floats and rasterises its own vertex
    // positions (projection times model-view, multiplied first); the shader turns normals by the model-view matrix and
    // projects its eye-space position: a few pixels a level apart, a few edge pixels covered by one part rather than
    // its neighbour (docs/architecture.md). On Mesa 22's llvmpipe: 11 of 64,000 pixels differ, 3 by more than 2.
    const ImageComparison anyDifference = compareImages(*instanced, *ordinary, 0);
    const ImageComparison difference = compareImages(*instanced, *ordinary, 2);
    ASSERT_TRUE(difference.comparable);
    EXPECT_LE(anyDifference.getShareOverTolerance(), 0.001) << anyDifference.numOverTolerance << " pixels differ";
    EXPECT_LE(difference.getShareOverTolerance(), 0.0005) << difference.numOverTolerance << " pixels over 2 levels";
    EXPECT_GT(difference.psnr, 45.0);
    EXPECT_GT(countDrawn(*instanced), 0.5 * instanced->s() * instanced->t());
}

TEST_F(InstancedImages, PartsAreDrawnInstancedFromBufferObjectsThoughTheirGeometryDrawsFromMemory)
{
    // The figure's shapes leave buffer objects off (osg::ShapeDrawable's default): the ordinary path reads their
    // arrays from memory, the instanced draw from the buffer objects OSG gives their arrays anyway (an instanced draw
    // from memory is far slower on NVIDIA's drivers, docs/performance.md).
    const std::vector<osg::Geometry*> geometries = partGeometries(*prototype);
    ASSERT_EQ(geometries.size(), numParts(*prototype));
    for (const osg::Geometry* geometry : geometries) ASSERT_FALSE(geometry->getUseVertexBufferObjects());
    const unsigned contextID = renderer->getCamera()->getGraphicsContext()->getState()->getContextID();
    drawOrdinaryPathWithTheSameShader();
    renderWith(InstancedActorGroup::ORDINARY);
    EXPECT_EQ(countVertexBuffersMade(geometries, contextID), 0u);
    expectTheSameBytes();
    EXPECT_EQ(countVertexBuffersMade(geometries, contextID), geometries.size());
    // Edited in place, a part's vertices reach its buffer object: every part flattened to a quarter of its width.
    const osg::ref_ptr<osg::Image> before = renderWith(InstancedActorGroup::INSTANCED);
    for (osg::Geometry* geometry : geometries)
    {
        osg::Vec3Array& vertices = static_cast<osg::Vec3Array&>(*geometry->getVertexArray());
        for (osg::Vec3& vertex : vertices) vertex.x() *= 0.25f;
        vertices.dirty();
        geometry->dirtyGLObjects(); // the ordinary path's display list
        geometry->dirtyBound();
    }
    expectTheSameBytes();
    const ImageComparison change = compareImages(*renderWith(InstancedActorGroup::INSTANCED), *before, 8);
    ASSERT_TRUE(change.comparable);
    EXPECT_GT(change.numOverTolerance, 1000u);
}

TEST_F(InstancedImages, PartsWhoseArraysHaveNoBufferObjectsAreDrawnInstancedFromMemory)
{
    // Buffer objects taken off the parts' arrays and element lists: the instanced draw reads them from memory, as
    // osg::Geometry would.
    for (osg::Geometry* geometry : partGeometries(*prototype))
    {
        for (osg::Array* array : {geometry->getVertexArray(), geometry->getNormalArray(), geometry->getColorArray()})
            if (array) array->setBufferObject(nullptr);
        for (unsigned i = 0; i < geometry->getNumPrimitiveSets(); ++i)
            if (osg::DrawElements* elements = geometry->getPrimitiveSet(i)->getDrawElements())
                elements->setBufferObject(nullptr);
    }
    drawOrdinaryPathWithTheSameShader();
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().instances, 4u * numParts(*prototype) + numPartsShown(*actors[3]));
}

TEST_F(InstancedImages, APoseChangedBetweenFramesShowsInTheInstancedImage)
{
    drawOrdinaryPathWithTheSameShader();
    const osg::ref_ptr<osg::Image> before = renderWith(InstancedActorGroup::INSTANCED);
    // Actor 2's left arm up sideways: pixels change where the arm was and is.
    actors[2]->setDof("l_shoulder.ry", -1.5);
    actors[2]->setDof("l_elbow.rx", -1.2);
    const osg::ref_ptr<osg::Image> after = renderWith(InstancedActorGroup::INSTANCED);
    const ImageComparison change = compareImages(*after, *before, 8);
    ASSERT_TRUE(change.comparable);
    EXPECT_GT(change.numOverTolerance, 200u);
    // And what it shows is what the ordinary path shows.
    expectTheSameBytes();
}

TEST_F(InstancedImages, AStillCrowdDrawnAgainGivesTheSameBytesFrameAfterFrame)
{
    // The instances' texture buffers come from a pool, one per frame in flight: the frames after the first reuse them.
    drawOrdinaryPathWithTheSameShader();
    const osg::ref_ptr<osg::Image> first = renderWith(InstancedActorGroup::INSTANCED);
    for (int frame = 0; frame < 3; ++frame)
    {
        const osg::ref_ptr<osg::Image> again = renderWith(InstancedActorGroup::INSTANCED);
        EXPECT_EQ(compareImages(*again, *first, 0).numOverTolerance, 0u) << "frame " << frame;
    }
}

TEST_F(InstancedImages, ACrowdOverSeveralSmallBuffersIsTheOrdinaryImageStillMovingAndShrinking)
{
    // Buffers of 5 instances: the frame is drawn from windows of the buffer the cull wrote, a batch's instances in
    // runs. Near and far not computed (the projection's own, about the crowd), so that a still actor adds the
    // instances it kept: where they were added last they are not written, and a frame with nothing written is not
    // uploaded again; a pose changed, or actors masked out and back (the instances move), write them again, and every
    // buffer shows what they now hold.
    osg::Camera& camera = *renderer->getCamera();
    camera.setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    double fovy = 0.0, aspect = 0.0, zNear = 0.0, zFar = 0.0;
    camera.getProjectionMatrixAsPerspective(fovy, aspect, zNear, zFar);
    camera.setProjectionMatrixAsPerspective(fovy, aspect, 0.5, 40.0);
    drawOrdinaryPathWithTheSameShader();
    group->setMaxTexelsPerBuffer(4 * 5);
    for (int frame = 0; frame < 3; ++frame) expectTheSameBytes();
    const InstancedActorGroup::Statistics statistics = group->getStatistics();
    EXPECT_EQ(statistics.texelLimit, 20u);
    // Actors 0 to 6, every part (of 3, every part shown): nothing is tested against the frustum below an actor.
    const unsigned all = 6u * numParts(*prototype) + numPartsShown(*actors[3]);
    EXPECT_EQ(statistics.actorsInstanced, 7u);
    EXPECT_EQ(statistics.instances, all);
    EXPECT_GE(statistics.buffers, (statistics.instances + 4u) / 5u);
    actors[2]->setDof("l_shoulder.ry", -1.5);
    actors[2]->setDof("l_elbow.rx", -1.2);
    for (int frame = 0; frame < 3; ++frame) expectTheSameBytes();
    actors[1]->setNodeMask(0u);
    actors[4]->setNodeMask(0u);
    for (int frame = 0; frame < 3; ++frame) expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().instances, all - 2u * numParts(*prototype));
    // Moved while two are away, then all back.
    actors[5]->setDof("r_shoulder.ry", 1.2);
    for (int frame = 0; frame < 2; ++frame) expectTheSameBytes();
    actors[1]->setNodeMask(~0u);
    actors[4]->setNodeMask(~0u);
    for (int frame = 0; frame < 3; ++frame) expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().instances, all);
}

TEST_F(InstancedImages, ACrowdGrowingBetweenFramesIsDrawnWhole)
{
    // One figure first (18 instances), then five (86): the frame's buffer of matrices, made for the first, grows.
    drawOrdinaryPathWithTheSameShader();
    for (unsigned a = 0; a < actors.size(); ++a)
        if (a != 2) actors[a]->setNodeMask(0u);
    renderWith(InstancedActorGroup::INSTANCED);
    EXPECT_EQ(group->getStatistics().instances, numParts(*prototype));
    for (osg::ref_ptr<ActorNode>& actor : actors) actor->setNodeMask(~0u);
    expectTheSameBytes();
    EXPECT_EQ(group->getStatistics().instances, 4u * numParts(*prototype) + numPartsShown(*actors[3]));
}

TEST_F(InstancedImages, CrowdFromAfarDropsTheSameSmallFeatures)
{
    // Small enough on screen for OSG's small-feature culling to drop the balls on the joints.
    renderer->setViewMatrixAsLookAt(osg::Vec3d(1.0, -60.0, 8.0), osg::Vec3d(0.0, 0.0, 0.8),
                                    osg::Vec3d(0.0, 0.0, 1.0));
    drawOrdinaryPathWithTheSameShader();
    expectTheSameBytes(0.001);
    EXPECT_LT(group->getStatistics().instances, 8u * numParts(*prototype));
}

TEST(InstancedActorText, HumanoidsOfColouredShapesAreTheOrdinaryImageUnderTheViewersColourMaterial)
{
    // data/humanoid.actor: shapes coloured per drawable (ShapeDrawable::setColor), lit through the colour material
    // of OSG's default state, as osgactorviewer shows them.
    const std::string file = std::string(OSGACTOR_TEST_DATA_DIR) + "/humanoid.actor";
    osg::ref_ptr<ActorNode> prototype = dynamic_cast<ActorNode*>(osgDB::readRefNodeFile(file).get());
    ASSERT_TRUE(prototype.valid()) << "cannot read " << file << " (is OSG_LIBRARY_PATH the build's lib?)";
    std::string error;
    osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(320, 200, error);
    ASSERT_TRUE(renderer) << error;
    renderer->setBackground(kBackground);
    osg::ref_ptr<InstancedActorGroup> group = new InstancedActorGroup;
    for (unsigned a = 0; a < 4; ++a)
    {
        osg::ref_ptr<ActorNode> actor = osg::clone(prototype.get(), osg::CopyOp::SHALLOW_COPY);
        actor->setPreTranslation(osg::Vec3d(0.8 * a - 1.2, 0.0, 0.0));
        actor->setDof(actor->getNumDofs() - 1, 0.3 * a);
        group->addChild(actor.get());
    }
    renderer->setScene(group.get());
    renderer->frameScene();
    group->setDrawMode(InstancedActorGroup::ORDINARY);
    const osg::ref_ptr<osg::Image> ordinary = renderer->renderFrame(0.0);
    group->setDrawMode(InstancedActorGroup::INSTANCED);
    const osg::ref_ptr<osg::Image> instanced = renderer->renderFrame(0.0);
    EXPECT_EQ(group->getStatistics().actorsInstanced, 4u);
    EXPECT_GT(group->getStatistics().instances, 4u * 10u);
    EXPECT_TRUE(matchesReference(*instanced, "humanoids_instanced"));
    const ImageComparison difference = compareImages(*instanced, *ordinary, 2);
    ASSERT_TRUE(difference.comparable);
    EXPECT_LE(difference.getShareOverTolerance(), 0.0005) << difference.numOverTolerance << " pixels over 2 levels";
    EXPECT_GT(countDrawn(*instanced), 0.05 * instanced->s() * instanced->t());
}
