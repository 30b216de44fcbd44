#include <osgActor/detail/InstancedCull.h>

#include <osgActor/ActorNode>
#include <osgActor/SkeletonNode>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/JointDrawBatch.h>
#include <osgActor/detail/PlacedSkeletonNode.h>

#include <osg/Material>
#include <osg/ShapeDrawable>
#include <osg/TextureBuffer>

#include <algorithm>
#include <typeinfo>

namespace osgActor {
namespace detail {

// --- InstancedFrame ---

InstancedFrame::InstancedFrame(osg::StateSet* programState, unsigned textureUnit)
    : _texels(new osg::Image), _stateSet(new osg::StateSet)
{
    _texels->allocateImage(256, 1, 1, GL_RGBA, GL_FLOAT);
    _texels->setInternalTextureFormat(GL_RGBA32F_ARB);
    osg::ref_ptr<osg::TextureBuffer> buffer = new osg::TextureBuffer(_texels.get());
    buffer->setInternalFormat(GL_RGBA32F_ARB);
    _stateSet->setTextureAttribute(textureUnit, buffer.get());
    _stateSet->merge(*programState);
}

bool InstancedFrame::isFree() const
{
    for (const osg::ref_ptr<InstancedDraw>& draw : _draws)
        if (draw->referenceCount() != 1) return false;
    return true;
}

float* InstancedFrame::reserveTexels(unsigned texels)
{
    if (static_cast<unsigned>(_texels->s()) < texels)
    {
        // Doubled, so that a growing crowd reallocates the buffer a few times, not every frame.
        unsigned size = static_cast<unsigned>(_texels->s());
        while (size < texels) size *= 2;
        _texels->allocateImage(static_cast<int>(size), 1, 1, GL_RGBA, GL_FLOAT);
    }
    return reinterpret_cast<float*>(_texels->data());
}

InstancedDraw* InstancedFrame::draw(unsigned i)
{
    while (_draws.size() <= i) _draws.push_back(new InstancedDraw);
    return _draws[i].get();
}

// --- InstancedCullState ---

void InstancedCullState::resizeGLObjectBuffers(unsigned maxSize)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->getStateSet()->resizeGLObjectBuffers(maxSize);
}

void InstancedCullState::releaseGLObjects(osg::State* state) const
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _frames) frame->getStateSet()->releaseGLObjects(state);
}

// --- InstancedCull ---

namespace {

bool isPlainGeometry(const osg::Drawable& drawable)
{
    const std::type_info& type = typeid(drawable);
    return !drawable.getCullCallback() && (type == typeid(osg::Geometry) || type == typeid(osg::ShapeDrawable)) &&
           InstancedDraw::canDraw(static_cast<const osg::Geometry&>(drawable));
}

/** Culling active at the node, but for its bound's validity, tested where the bound is used (as ActorCullPlan). */
bool isCullingActive(const osg::Node& node)
{
    return node.getCullingActive() && node.getNumChildrenWithCullingDisabled() == 0;
}

} // namespace

bool InstancedCull::isInstanceableState(const osg::StateSet* state)
{
    if (!state) return true;
    if (!state->getTextureAttributeList().empty() || !state->getTextureModeList().empty() ||
        !state->getUniformList().empty() || state->getRenderBinMode() != osg::StateSet::INHERIT_RENDERBIN_DETAILS ||
        !state->getDefineList().empty())
        return false;
    for (const auto& attribute : state->getAttributeList())
    {
        const osg::Material* material = dynamic_cast<const osg::Material*>(attribute.second.first.get());
        if (!material || material->getColorMode() != osg::Material::OFF) return false;
    }
    return (state->getMode(GL_LIGHTING) & osg::StateAttribute::ON) != 0 ||
           state->getMode(GL_LIGHTING) == osg::StateAttribute::INHERIT;
}

InstancedCull::InstancedCull(osgUtil::CullVisitor& cv, InstancedCullState& state, osg::Group& group,
                             osg::StateSet* programState, unsigned textureUnit)
    : _cv(cv), _state(state), _programState(programState), _traversalMask(cv.getTraversalMask()),
      _maskOverride(cv.getNodeMaskOverride()),
      _smallFeatureCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::SMALL_FEATURE_CULLING) != 0),
      _computeNearFar(cv.getComputeNearFarMode() != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR),
      _frustumCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING) != 0),
      _smallFeaturePixelSize(cv.getCurrentCullingSet().getSmallFeatureCullingPixelSize())
{
    _state._statistics = InstancedCullState::Statistics();
    for (InstancedCullState::Batch& batch : _state._batches) batch.matrices.clear();
    for (unsigned i = 0; i < group.getNumChildren(); ++i)
    {
        osg::Node& child = *group.getChild(i);
        ActorNode* actor = typeid(child) == typeid(ActorNode) ? static_cast<ActorNode*>(&child) : nullptr;
        if (!actor || !gatherParts(*actor))
        {
            if (actor) ++_state._statistics.actorsOrdinary;
            child.accept(cv);
            continue;
        }
        ++_state._statistics.actorsInstanced;
        // What the visitor does on its way into the actor: its mask, then its bound in the group's frame.
        if (!_cv.isCulled(*actor) && _cv.validNodeMask(*actor)) cullActor(*actor);
    }
    emitBatches(textureUnit);
}

bool InstancedCull::gatherParts(ActorNode& actor)
{
    _state._joints.clear();
    _state._geodes.clear();
    if (actor.getCullMode() != ActorNode::CULL_AS_ONE || actor.getCullCallback() || actor.getStateSet() ||
        actor.getReferenceFrame() != osg::Transform::RELATIVE_RF || !isCullingActive(actor))
        return false;
    for (unsigned i = 0; i < actor.getNumChildren(); ++i)
        if (!gatherChild(*actor.getChild(i), -1)) return false;
    return true;
}

bool InstancedCull::gatherChild(osg::Node& child, int joint)
{
    const std::type_info& type = typeid(child);
    if (type == typeid(PlacedSkeletonNode) || type == typeid(SkeletonNode))
    {
        SkeletonNode& node = static_cast<SkeletonNode&>(child);
        if (node.getHidden() || node.getCullCallback() || node.getStateSet() ||
            node.getReferenceFrame() != osg::Transform::RELATIVE_RF || !isCullingActive(node))
            return false;
        const int index = static_cast<int>(_state._joints.size());
        _state._joints.push_back({&node, joint});
        for (unsigned i = 0; i < node.getNumChildren(); ++i)
            if (!gatherChild(*node.getChild(i), index)) return false;
        return true;
    }
    if (type != typeid(osg::Geode) || joint < 0 || child.getCullCallback() || !isCullingActive(child) ||
        !isInstanceableState(child.getStateSet()))
        return false;
    osg::Geode& geode = static_cast<osg::Geode&>(child);
    for (unsigned i = 0; i < geode.getNumChildren(); ++i)
    {
        const osg::Drawable* drawable = geode.getChild(i)->asDrawable();
        if (!drawable || !isPlainGeometry(*drawable) || !isInstanceableState(drawable->getStateSet())) return false;
    }
    _state._geodes.push_back({&geode, joint});
    return true;
}

bool InstancedCull::isSmallFeature(const osg::Node& node, unsigned frame)
{
    if (!_smallFeatureCulling) return false;
    const osg::BoundingSphere& bound = node.getBound();
    if (!bound.valid()) return false; // the visitor never tests it (the node is not culling-active)
    if (!_state._hasPixelSizeVector[frame])
    {
        // As osg::CullStack::pushCullingSet() makes it for this matrix.
        _state._pixelSizeVectors[frame] = osg::CullingSet::computePixelSizeVector(
            *_cv.getViewport(), *_cv.getProjectionMatrix(), _state._modelViews[frame]);
        _state._hasPixelSizeVector[frame] = 1;
    }
    return detail::isSmallFeature(bound, _state._pixelSizeVectors[frame], _smallFeaturePixelSize);
}

void InstancedCull::cullActor(ActorNode& actor)
{
    const std::vector<InstancedCullState::Joint>& joints = _state._joints;
    const std::size_t numFrames = joints.size() + 1;
    _state._modelViews.resize(numFrames);
    _state._hasPixelSizeVector.assign(numFrames, 0);
    _state._pixelSizeVectors.resize(numFrames);
    _state._jointCulled.assign(joints.size(), 0);
    // The actor's frame, as the visitor's pushModelViewMatrix() makes it (MatrixTransform: actor_m * group's).
    std::vector<osg::Matrixd>& modelViews = _state._modelViews;
    composeModelView(actor.getMatrix().ptr(), _cv.getModelViewMatrix()->ptr(), modelViews[0].ptr());
    if (actor.getUpdatePolicy().onlyWhenSeen)
    {
        // The update policy notes the view with the actor's frame on the visitor's stack, as its own cull does.
        _cv.pushModelViewMatrix(new osg::RefMatrix(modelViews[0]), osg::Transform::RELATIVE_RF);
        actor.noteSeen(_cv);
        _cv.popModelViewMatrix();
    }
    for (std::size_t j = 0; j < joints.size(); ++j)
    {
        const unsigned parentFrame = static_cast<unsigned>(joints[j].parent + 1);
        composeModelView(joints[j].node->getMatrix().ptr(), modelViews[parentFrame].ptr(), modelViews[j + 1].ptr());
        // A joint masked out or too small in its parent's frame is culled with everything below it (parents first).
        _state._jointCulled[j] = (joints[j].parent >= 0 && _state._jointCulled[joints[j].parent]) ||
                                 isMasked(*joints[j].node) || isSmallFeature(*joints[j].node, parentFrame);
    }
    const osg::Polytope& frustum = _cv.getProjectionCullingStack().back().getFrustum();
    for (const InstancedCullState::Geode& part : _state._geodes)
    {
        const unsigned frame = static_cast<unsigned>(part.joint + 1);
        if (_state._jointCulled[part.joint] || isMasked(*part.geode) || isSmallFeature(*part.geode, frame)) continue;
        const osg::Matrixd& modelView = modelViews[frame];
        for (unsigned i = 0; i < part.geode->getNumChildren(); ++i)
        {
            const osg::Geometry& drawable = *static_cast<const osg::Geometry*>(part.geode->getChild(i)->asDrawable());
            if (isMasked(drawable)) continue;
            // As ActorCull::addDrawable(): near and far from what is drawn, the box against the frustum before.
            const osg::BoundingBox& box = drawable.getBoundingBox();
            if (_computeNearFar && box.valid())
            {
                if (_frustumCulling && isCullingActive(drawable) && isOutsideFrustum(box, modelView, frustum))
                    continue;
                if (!_cv.updateCalculatedNearFar(modelView, drawable, true)) continue;
            }
            if (box.valid() && osg::isNaN(eyeDepth(box.center(), modelView))) continue; // the visitor drops it too
            addInstance(part.geode->getStateSet(), drawable, modelView);
        }
    }
}

void InstancedCull::addInstance(const osg::StateSet* geodeState, const osg::Geometry& drawable,
                                const osg::Matrixd& modelView)
{
    auto found = _state._batchOfKey.emplace(InstancedCullState::BatchKey{geodeState, &drawable},
                                            static_cast<unsigned>(_state._batches.size()));
    if (found.second) _state._batches.push_back({geodeState, &drawable, {}});
    std::vector<float>& matrices = _state._batches[found.first->second].matrices;
    const double* m = modelView.ptr();
    // As OSG hands a matrix to OpenGL (glLoadMatrixd, which keeps floats): each double rounded to the nearest float.
    for (int k = 0; k < 16; ++k) matrices.push_back(static_cast<float>(m[k]));
}

InstancedFrame* InstancedCull::acquireFrame(unsigned textureUnit)
{
    for (const osg::ref_ptr<InstancedFrame>& frame : _state._frames)
        if (frame->isFree()) return frame.get();
    _state._frames.push_back(new InstancedFrame(_programState, textureUnit));
    return _state._frames.back().get();
}

void InstancedCull::emitBatches(unsigned textureUnit)
{
    unsigned texels = 0;
    for (const InstancedCullState::Batch& batch : _state._batches)
        texels += static_cast<unsigned>(batch.matrices.size() / 4);
    if (texels == 0) return;
    InstancedFrame& frame = *acquireFrame(textureUnit);
    float* out = frame.reserveTexels(texels);
    unsigned base = 0, drawIndex = 0;
    osg::RefMatrix* groupModelView = _cv.getModelViewMatrix();
    for (const InstancedCullState::Batch& batch : _state._batches)
    {
        const unsigned count = static_cast<unsigned>(batch.matrices.size() / 16);
        if (count == 0) continue;
        std::copy(batch.matrices.begin(), batch.matrices.end(), out + 4 * base);
        InstancedDraw* draw = frame.draw(drawIndex++);
        draw->set(batch.drawable, static_cast<int>(base), count);
        base += 4 * count;
        // The drawable's states as the ordinary traversal pushes them (the geode's, then its own), then the frame's.
        if (batch.geodeState) _cv.pushStateSet(batch.geodeState);
        if (const osg::StateSet* own = batch.drawable->getStateSet()) _cv.pushStateSet(own);
        _cv.pushStateSet(frame.getStateSet());
        // The leaf's matrix is the group's: the program takes each instance's from the buffer, the projection from
        // the leaf.
        _cv.addDrawableAndDepth(draw, groupModelView, 0.0f);
        _cv.popStateSet();
        if (batch.drawable->getStateSet()) _cv.popStateSet();
        if (batch.geodeState) _cv.popStateSet();
        ++_state._statistics.draws;
        _state._statistics.instances += count;
    }
    frame.dirty();
}

} // namespace detail
} // namespace osgActor
