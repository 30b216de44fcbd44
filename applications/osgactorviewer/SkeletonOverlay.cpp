#include "SkeletonOverlay.h"

#include <osg/Depth>
#include <osg/LineWidth>

#include <algorithm>

namespace osgActorViewer {

namespace {

struct RebuildEachFrame : public osg::NodeCallback
{
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override
    {
        static_cast<SkeletonOverlay*>(node)->rebuild();
        traverse(node, nv);
    }
};

const osg::Vec4 kBoneColour(1.0f, 1.0f, 0.3f, 1.0f);

} // namespace

SkeletonOverlay::SkeletonOverlay(osgActor::ActorNode* actor)
    : _actor(actor), _geometry(new osg::Geometry), _vertices(new osg::Vec3Array), _colours(new osg::Vec4Array),
      _lines(new osg::DrawArrays(GL_LINES)), _showAxes(false), _showLines(false), _selectedJoint(-1)
{
    _axisLength = std::max(0.01, 0.06 * actor->getBound().radius());

    // Rewritten every frame while the previous frame may still be drawn: dynamic, and no display list.
    _geometry->setDataVariance(osg::Object::DYNAMIC);
    _geometry->setUseDisplayList(false);
    _geometry->setUseVertexBufferObjects(true);
    _geometry->setVertexArray(_vertices.get());
    _geometry->setColorArray(_colours.get(), osg::Array::BIND_PER_VERTEX);
    _geometry->addPrimitiveSet(_lines.get());
    addDrawable(_geometry.get());

    osg::StateSet* state = getOrCreateStateSet();
    state->setMode(GL_LIGHTING, osg::StateAttribute::OFF | osg::StateAttribute::PROTECTED);
    state->setAttributeAndModes(new osg::Depth(osg::Depth::ALWAYS), osg::StateAttribute::ON);
    state->setAttributeAndModes(new osg::LineWidth(2.0f));
    state->setRenderBinDetails(1000, "RenderBin"); // after the scene, so that nothing covers the lines
    setUpdateCallback(new RebuildEachFrame);
    setCullingActive(false); // the bound changes every frame
}

void SkeletonOverlay::addAxes(const osg::Matrixd& joint, double length)
{
    const osg::Vec3d origin = joint.getTrans();
    for (int axis = 0; axis < 3; ++axis)
    {
        osg::Vec3d direction;
        direction[axis] = 1.0;
        osg::Vec4 colour(0.0f, 0.0f, 0.0f, 1.0f);
        colour[axis] = 1.0f;
        _vertices->push_back(origin);
        _vertices->push_back(osg::Matrixd::transform3x3(direction, joint) * length + origin);
        _colours->push_back(colour);
        _colours->push_back(colour);
    }
}

void SkeletonOverlay::rebuild()
{
    _vertices->clear();
    _colours->clear();
    osg::ref_ptr<osgActor::ActorNode> actor;
    if (_actor.lock(actor) && actor->getDefinition())
    {
        const osgActor::ActorDefinition& definition = *actor->getDefinition();
        for (unsigned joint = 0; joint < definition.getNumJoints(); ++joint)
        {
            const osg::Matrixd world = actor->getJointWorldMatrix(joint);
            const int parent = definition.getParent(joint);
            if (_showLines && parent != osgActor::kNoParent)
            {
                _vertices->push_back(actor->getJointWorldPosition(unsigned(parent)));
                _vertices->push_back(world.getTrans());
                _colours->push_back(kBoneColour);
                _colours->push_back(kBoneColour);
            }
            if (_showAxes) addAxes(world, _axisLength);
            if (int(joint) == _selectedJoint) addAxes(world, 3.0 * _axisLength);
        }
    }
    _lines->setCount(GLsizei(_vertices->size()));
    _vertices->dirty();
    _colours->dirty();
    _geometry->dirtyBound();
}

} // namespace osgActorViewer
