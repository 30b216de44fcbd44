#include <osgActor/StickFigure>

#include <osg/Geode>
#include <osg/Geometry>
#include <osg/LineWidth>
#include <osg/Material>
#include <osg/ShapeDrawable>

#include <algorithm>
#include <vector>

namespace osgActor {

namespace {

/** The extent of the rest pose: the diagonal of the box around every joint origin (model space). */
double restPoseSize(const ActorDefinitionPtr& definition)
{
    ActorPose rest(definition);
    rest.updateMatrices();
    osg::BoundingBoxd box;
    for (unsigned j = 0; j < rest.getNumJoints(); ++j)
    {
        const glm::dvec4& p = rest.getModelMatrix(j)[3];
        box.expandBy(osg::Vec3d(p.x, p.y, p.z));
    }
    return box.valid() ? box.radius() * 2.0 : 0.0;
}

osg::ref_ptr<osg::Geode> makeBall(double radius)
{
    osg::ref_ptr<osg::ShapeDrawable> ball =
        new osg::ShapeDrawable(new osg::Sphere(osg::Vec3(), static_cast<float>(radius)));
    ball->setColor(osg::Vec4(0.9f, 0.6f, 0.2f, 1.0f));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("joint ball");
    geode->addDrawable(ball.get());
    return geode;
}

osg::ref_ptr<osg::Geode> makeBones(const std::vector<osg::Vec3>& ends)
{
    osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
    for (const osg::Vec3& end : ends)
    {
        vertices->push_back(osg::Vec3());
        vertices->push_back(end);
    }
    osg::ref_ptr<osg::Geometry> lines = new osg::Geometry;
    lines->setVertexArray(vertices.get());
    osg::ref_ptr<osg::Vec4Array> colors = new osg::Vec4Array;
    colors->push_back(osg::Vec4(0.85f, 0.85f, 0.9f, 1.0f));
    lines->setColorArray(colors.get(), osg::Array::BIND_OVERALL);
    lines->addPrimitiveSet(new osg::DrawArrays(GL_LINES, 0, static_cast<GLsizei>(vertices->size())));
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("bones");
    geode->addDrawable(lines.get());
    osg::StateSet* state = geode->getOrCreateStateSet();
    state->setMode(GL_LIGHTING, osg::StateAttribute::OFF);
    state->setAttributeAndModes(new osg::LineWidth(2.0f));
    return geode;
}

} // namespace

double addStickFigure(ActorNode& actor, double radius)
{
    const ActorDefinitionPtr& definition = actor.getDefinition();
    if (!definition) return 0.0;
    const double size = restPoseSize(definition);
    if (!(radius > 0.0)) radius = std::max(0.015 * size, 1e-6);
    osg::ref_ptr<osg::Geode> ball = makeBall(radius);
    // Each child's offset translation is where its bone ends in the parent joint's frame.
    std::vector<std::vector<osg::Vec3>> boneEnds(definition->getNumJoints());
    for (unsigned j = 0; j < definition->getNumJoints(); ++j)
    {
        const int parent = definition->getParent(j);
        const glm::dvec3& t = definition->getOffsetTranslation(j);
        if (parent >= 0) boneEnds[static_cast<unsigned>(parent)].push_back(osg::Vec3(t.x, t.y, t.z));
    }
    for (unsigned j = 0; j < actor.getNumSkeletonNodes(); ++j)
    {
        SkeletonNode* node = actor.getSkeletonNode(j);
        node->addChild(ball.get());
        if (!boneEnds[j].empty()) node->addChild(makeBones(boneEnds[j]).get());
    }
    return size;
}

} // namespace osgActor
