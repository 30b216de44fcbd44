#include "SkinDrawTestUtil"

#include <osgActor/core/ActorDefinitionBuilder>

#include <glm/gtc/matrix_transform.hpp>

#include <osg/Geode>
#include <osgUtil/RenderStage>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace osgActor {
namespace test {

namespace {

FrameDriver::CulledLeaf culledLeafOf(const osgUtil::RenderLeaf& leaf)
{
    FrameDriver::CulledLeaf culled{leaf.getDrawable(), {}, leaf._dynamic};
    for (const osgUtil::StateGraph* graph = leaf._parent; graph; graph = graph->_parent)
    {
        if (graph->getStateSet()) culled.stateSets.insert(culled.stateSets.begin(), graph->getStateSet());
        culled.dynamic = culled.dynamic || graph->_dynamic;
    }
    return culled;
}

/** The leaves of a render bin and of the bins inside it. */
void collectLeaves(const osgUtil::RenderBin& bin, std::vector<FrameDriver::CulledLeaf>& leaves)
{
    for (const osgUtil::RenderLeaf* leaf : bin.getRenderLeafList()) leaves.push_back(culledLeafOf(*leaf));
    for (const osgUtil::StateGraph* graph : bin.getStateGraphList())
        for (const osg::ref_ptr<osgUtil::RenderLeaf>& leaf : graph->_leaves) leaves.push_back(culledLeafOf(*leaf));
    for (const auto& child : bin.getRenderBinList()) collectLeaves(*child.second, leaves);
}

/** A SkinnedMesh of a source's skin in a Geode below a new actor of the definition; triangles as given. */
SyntheticActor makeActor(const ActorDefinitionPtr& definition, SkinSource source, SkinningMethod method,
                         const std::vector<unsigned>& triangles)
{
    SyntheticActor made;
    made.source = std::move(source);
    SkinBuildResult built = made.source.toBuilder("synthetic", method).build();
    EXPECT_TRUE(built) << built.error;
    made.skin = built.skin;
    osg::ref_ptr<osg::Geometry> surface = new osg::Geometry;
    surface->addPrimitiveSet(new osg::DrawElementsUInt(GL_TRIANGLES, triangles.begin(), triangles.end()));
    made.mesh = new SkinnedMesh(made.skin, surface.get());
    made.mesh->setName("synthetic");
    made.actor = new ActorNode(definition);
    made.actor->setName("synthetic");
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(made.mesh.get());
    made.actor->addChild(geode.get());
    return made;
}

} // namespace

std::string cesiumManFile() { return std::string(OSGACTOR_TEST_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf"; }

RiggedModelActor readCesiumMan(SkinnedMesh::SkinningPath path)
{
    RiggedModelActorOptions options;
    options.skinning = path;
    std::string error;
    RiggedModelActor read = readRiggedModelActor(cesiumManFile(), options, error);
    EXPECT_TRUE(read.actor) << error;
    EXPECT_EQ(read.skinnedMeshes.size(), 1u);
    return read;
}

SkinSource cesiumManSkinSource(const RiggedModelActor& read)
{
    const SkinnedPrimitive& skinned = read.rigged.skins.at(0);
    const RiggedPrimitive& primitive = read.rigged.model->meshes[skinned.mesh].primitives[skinned.primitive];
    SkinSource source;
    source.jointNames = skinned.skin->getJointNames();
    for (unsigned j = 0; j < skinned.skin->getNumJoints(); ++j)
        source.inverseBindMatrices.push_back(skinned.skin->getInverseBindMatrix(j));
    source.positions = primitive.positions;
    source.normals = primitive.normals;
    const unsigned perVertex = primitive.influencesPerVertex;
    for (std::size_t v = 0; v < primitive.positions.size(); ++v)
    {
        std::vector<std::pair<unsigned, double>> influences;
        double sum = 0.0;
        for (unsigned k = 0; k < perVertex; ++k)
        {
            const double w = primitive.weights[v * perVertex + k];
            if (w == 0.0) continue;
            influences.push_back({primitive.joints[v * perVertex + k], w});
            sum += w;
        }
        for (auto& influence : influences) influence.second /= sum;
        source.influences.push_back(influences);
    }
    return source;
}

SyntheticActor makeChainActor(unsigned numJoints, SkinningMethod method, double bindScale)
{
    ActorDefinitionBuilder builder("chain");
    for (unsigned j = 0; j < numJoints; ++j)
        builder.addJoint("j" + std::to_string(j), j == 0 ? std::string() : "j" + std::to_string(j - 1))
            .offset(j == 0 ? 0.0 : 0.1, 0.0, 0.0)
            .dofs(Dof::RY | Dof::RZ);
    ActorDefinitionPtr definition = builder.build().definition;
    const unsigned rings = 4, sides = 6;
    SkinSource source = makeTubeSkin(*definition, rings, sides, 0.3, 0.01);
    // The mesh authored in units 1 / bindScale of the model's: its bind positions (mesh units) bindScale times
    // smaller, each inverse bind matrix (similarity scale bindScale, the skin's bind scale) scaling them back first,
    // so that the skinned mesh is where it was.
    for (glm::dmat4& inverseBind : source.inverseBindMatrices)
        inverseBind = inverseBind * glm::scale(glm::dmat4(1.0), glm::dvec3(bindScale));
    for (glm::vec3& position : source.positions) position /= static_cast<float>(bindScale);
    // Each bone's rings x sides vertices come together; quads between its consecutive rings.
    std::vector<unsigned> triangles;
    const unsigned perBone = rings * sides;
    for (unsigned bone = 0; bone < source.positions.size() / perBone; ++bone)
        for (unsigned ring = 0; ring + 1 < rings; ++ring)
            for (unsigned k = 0; k < sides; ++k)
            {
                const unsigned a = bone * perBone + ring * sides + k;
                const unsigned b = bone * perBone + ring * sides + (k + 1) % sides;
                triangles.insert(triangles.end(), {a, b, a + sides, b, b + sides, a + sides});
            }
    return makeActor(definition, std::move(source), method, triangles);
}

SyntheticActor makeRandomActor(unsigned numJoints, unsigned numVertices, unsigned influences, std::uint32_t seed,
                               SkinningMethod method)
{
    ActorDefinitionPtr definition = makeRandomDefinition(numJoints, seed);
    SkinSource source = makeRandomSkin(*definition, numVertices, influences, seed + 1);
    std::vector<unsigned> triangles(numVertices - numVertices % 3);
    for (unsigned i = 0; i < triangles.size(); ++i) triangles[i] = i;
    return makeActor(definition, std::move(source), method, triangles);
}

void poseSynthetic(ActorNode& actor, double t)
{
    for (unsigned d = 0; d < actor.getNumDofs(); ++d) actor.setDof(d, 0.6 * std::sin(1.3 * t + 0.7 * d));
}

FrameDriver::FrameDriver(osg::Node* scene, int width, int height)
    : _scene(scene), _stamp(new osg::FrameStamp), _update(new osgUtil::UpdateVisitor),
      _sceneView(new osgUtil::SceneView)
{
    _update->setFrameStamp(_stamp.get());
    _sceneView->setDefaults(osgUtil::SceneView::STANDARD_SETTINGS);
    _sceneView->setSceneData(scene);
    _sceneView->setFrameStamp(_stamp.get());
    _sceneView->setViewport(0, 0, width, height);
    lookAt(osg::Vec3d(0, -6, 1), osg::Vec3d(0, 0, 1), osg::Vec3d(0, 0, 1));
}

void FrameDriver::lookAt(const osg::Vec3d& eye, const osg::Vec3d& center, const osg::Vec3d& up, double fovy)
{
    const osg::Viewport* viewport = _sceneView->getViewport();
    _sceneView->setProjectionMatrixAsPerspective(fovy, viewport->width() / viewport->height(), 0.01, 1000.0);
    _sceneView->setViewMatrixAsLookAt(eye, center, up);
}

void FrameDriver::update(double t)
{
    ++_frameNumber;
    _stamp->setFrameNumber(_frameNumber);
    _stamp->setSimulationTime(t);
    _stamp->setReferenceTime(t);
    _update->setTraversalNumber(_frameNumber);
    _scene->accept(*_update);
    _scene->getBound(); // as osgViewer does at the end of its update traversal
}

void FrameDriver::cull() { _sceneView->cull(); }

void FrameDriver::frame(double t)
{
    update(t);
    cull();
}

std::vector<FrameDriver::CulledLeaf> FrameDriver::culledLeaves() const
{
    std::vector<CulledLeaf> leaves;
    collectLeaves(*_sceneView->getRenderStage(), leaves);
    return leaves;
}

std::vector<const osg::Drawable*> FrameDriver::culledDrawables() const
{
    std::vector<const osg::Drawable*> drawables;
    for (const CulledLeaf& leaf : culledLeaves()) drawables.push_back(leaf.drawable);
    return drawables;
}

double maxDistance(const osg::Vec3Array& a, const std::vector<ReferenceVertex>& reference)
{
    double largest = 0.0;
    for (std::size_t v = 0; v < a.size(); ++v)
        largest = std::max(largest, glm::length(glm::dvec3(a[v].x(), a[v].y(), a[v].z()) - reference[v].position));
    return largest;
}

double maxDistance(const osg::Vec3Array& a, const osg::Vec3Array& b)
{
    double largest = 0.0;
    for (std::size_t v = 0; v < a.size(); ++v) largest = std::max(largest, double((a[v] - b[v]).length()));
    return largest;
}

bool holdsEvery(const osg::BoundingBox& box, const osg::Vec3Array& points)
{
    for (const osg::Vec3& p : points)
        if (!box.contains(p)) return false;
    return true;
}

std::vector<ReferenceVertex> referenceSkinning(const SkinSource& source, const Skin& skin, const ActorNode& actor)
{
    actor.updatePose();
    const std::vector<glm::dmat4> matrices = referenceSkinningMatrices(actor.getPose(), source);
    if (skin.getMethod() == SkinningMethod::DualQuaternion)
        return referenceDualQuaternion(source, matrices, skin.getBindScale());
    return referenceLinearBlend(source, matrices, skin.getNormalTransform() == NormalTransform::InverseTranspose);
}

} // namespace test
} // namespace osgActor
