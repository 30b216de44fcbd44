#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/PlacedSkeletonNode.h>

#include <osg/Geometry>
#include <osg/Math>
#include <osg/ShapeDrawable>

#include <typeinfo>

namespace osgActor {
namespace detail {

namespace {

/** A point's depth in front of the eye, as the cull visitor computes it for the render graph's depth sorting (its
  * own function is private to it): minus the eye-space z. */
float eyeDepth(const osg::Vec3& point, const osg::Matrixd& modelView)
{
    using Value = osgUtil::CullVisitor::value_type;
    return static_cast<float>(-(static_cast<Value>(point[0]) * modelView(0, 2) +
                                static_cast<Value>(point[1]) * modelView(1, 2) +
                                static_cast<Value>(point[2]) * modelView(2, 2) + modelView(3, 2)));
}

/** The cull visitor's pool of model-view matrices (matrices the render graph holds until the frame is drawn, reused
  * once it lets go of them): osg::CullStack::createOrReuseMatrix() is protected, and a pointer to it formed in a
  * class derived from CullStack may be called on any CullStack. Never instantiated. */
struct MatrixPool : osg::CullStack
{
    static osg::RefMatrix* createOrReuse(osg::CullStack& stack, const osg::Matrix& value)
    {
        osg::RefMatrix* (osg::CullStack::*const create)(const osg::Matrix&) = &MatrixPool::createOrReuseMatrix;
        return (stack.*create)(value);
    }
};

} // namespace

bool ActorCull::canCullAsOne(osgUtil::CullVisitor& cv)
{
    if (typeid(cv) != typeid(osgUtil::CullVisitor)) return false;
    return cv.getOccluderList().empty() && cv.getCurrentCullingSet().getStateFrustumList().empty();
}

ActorCull::ActorCull(osgUtil::CullVisitor& cv)
    : _cv(cv),
      _smallFeatureCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::SMALL_FEATURE_CULLING) != 0),
      _computeNearFar(cv.getComputeNearFarMode() != osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR),
      _frustumCulling((cv.getCurrentCullingSet().getCullingMask() & osg::CullingSet::VIEW_FRUSTUM_CULLING) != 0),
      _open(), _numOpen(0)
{
}

void ActorCull::cullChildren(osg::Group& actor)
{
    // The actor's own frame is on the visitor's stacks already (it pushed actor_m on its way in).
    JointFrame frame;
    frame.modelView = *_cv.getModelViewMatrix();
    frame.leafMatrix = _cv.getModelViewMatrix();
    frame.pixelSizeVector = _cv.getCurrentCullingSet().getPixelSizeVector();
    frame.hasPixelSizeVector = true;
    frame.pushed = true;
    for (unsigned i = 0; i < actor.getNumChildren(); ++i) cullChild(*actor.getChild(i), frame);
}

bool ActorCull::isPlainJoint(const SkeletonNode& joint)
{
    return isPlain(joint) && !joint.getHidden() && joint.getReferenceFrame() == osg::Transform::RELATIVE_RF;
}

bool ActorCull::isPlainDrawable(const osg::Drawable& drawable)
{
    const std::type_info& type = typeid(drawable);
    return isPlain(drawable) && (type == typeid(osg::Geometry) || type == typeid(osg::ShapeDrawable));
}

void ActorCull::cullChild(osg::Node& child, JointFrame& frame)
{
    if (!_cv.validNodeMask(child)) return; // as Node::accept() would
    // Exact classes only: a subclass may traverse, cull or draw in its own way.
    const std::type_info& type = typeid(child);
    if (type == typeid(PlacedSkeletonNode) || type == typeid(SkeletonNode))
    {
        SkeletonNode& joint = static_cast<SkeletonNode&>(child);
        if (isPlainJoint(joint))
        {
            cullJoint(joint, frame);
            return;
        }
    }
    else if (type == typeid(osg::Geode) && isPlain(child))
    {
        cullGeode(static_cast<osg::Geode&>(child), frame);
        return;
    }
    traverseOrdinarily(child, frame);
}

void ActorCull::cullJoint(SkeletonNode& joint, JointFrame& parent)
{
    // The visitor tests the node's sphere in the parent's frame; a small feature is culled with its subtree.
    if (_smallFeatureCulling && joint.isCullingActive() && isSmallFeature(joint.getBound(), parent)) return;
    JointFrame frame;
    frame.modelView = parent.modelView;
    joint.computeLocalToWorldMatrix(frame.modelView, &_cv); // what CullVisitor::apply(osg::Transform&) calls
    frame.leafMatrix = nullptr;
    frame.hasPixelSizeVector = false;
    frame.pushed = false;
    // Cull callbacks and user nodes below may read the node path: keep it as the ordinary traversal does.
    _cv.pushOntoNodePath(&joint);
    osg::StateSet* state = joint.getStateSet();
    if (state) _cv.pushStateSet(state);
    for (unsigned i = 0; i < joint.getNumChildren(); ++i) cullChild(*joint.getChild(i), frame);
    if (state) _cv.popStateSet();
    _cv.popFromNodePath();
    if (frame.pushed) _cv.popModelViewMatrix();
}

void ActorCull::cullGeode(osg::Geode& geode, JointFrame& frame)
{
    if (_smallFeatureCulling && geode.isCullingActive() && isSmallFeature(geode.getBound(), frame)) return;
    _cv.pushOntoNodePath(&geode);
    osg::StateSet* state = geode.getStateSet();
    if (state) _cv.pushStateSet(state);
    for (unsigned i = 0; i < geode.getNumChildren(); ++i)
    {
        osg::Node& child = *geode.getChild(i);
        osg::Drawable* drawable = child.asDrawable();
        if (drawable && isPlainDrawable(*drawable))
        {
            if (_cv.validNodeMask(*drawable)) addDrawable(*drawable, frame);
        }
        else
            traverseOrdinarily(child, frame);
    }
    if (state) _cv.popStateSet();
    _cv.popFromNodePath();
}

void ActorCull::addDrawable(osg::Drawable& drawable, JointFrame& frame)
{
    // What CullVisitor::apply(osg::Drawable&) does for a drawable without a cull callback, with the
    // frustum test kept where it changes the image: near and far planes computed from what is drawn.
    const osg::BoundingBox& box = drawable.getBoundingBox();
    if (_computeNearFar && box.valid())
    {
        if (_frustumCulling && drawable.isCullingActive() && isOutsideFrustum(box, frame.modelView)) return;
        // The visitor takes the box's nearest and farthest corners along the view in the frame of the matrix it last
        // pushed, which here is the actor's, not the joint's: its billboard form finds them from the matrix given,
        // with the same arithmetic pushModelViewMatrix() uses, so the planes are those of the ordinary traversal.
        if (!_cv.updateCalculatedNearFar(frame.modelView, drawable, true)) return;
    }
    const float depth = box.valid() ? eyeDepth(box.center(), frame.modelView) : 0.0f;
    if (osg::isNaN(depth)) return; // the visitor drops it too (with a notice)
    osg::StateSet* state = drawable.getStateSet();
    if (state) _cv.pushStateSet(state);
    osgUtil::StateGraph* graph = _cv.getCurrentStateGraph();
    // Batched where the bin draws its state graphs' leaves in the order they came: a bin sorted by state. Dynamic
    // drawables keep a leaf of their own, which tells a viewer drawing on another thread to wait for them.
    const bool batchable = _cv.getCurrentRenderBin()->getSortMode() == osgUtil::RenderBin::SORT_BY_STATE &&
                           drawable.getDataVariance() != osg::Object::DYNAMIC &&
                           !(state && state->getDataVariance() == osg::Object::DYNAMIC);
    JointDrawBatch* batch = batchable ? openBatch(graph) : nullptr;
    if (batch)
        batch->add(drawable, frame.modelView, depth);
    else
    {
        if (!frame.leafMatrix) frame.leafMatrix = MatrixPool::createOrReuse(_cv, frame.modelView);
        if (batchable)
        {
            // The batch's leaf carries the first drawable's matrix, so the state graph's state is applied under the
            // matrix it would be applied under without the batch.
            batch = JointDrawBatch::acquire();
            batch->add(drawable, frame.modelView, depth);
            _cv.addDrawableAndDepth(batch, frame.leafMatrix, depth);
            if (_numOpen == kMaxOpenBatches) closeBatch(_open[0].graph);
            _open[_numOpen++] = {graph, batch};
        }
        else
        {
            closeBatch(graph);
            _cv.addDrawableAndDepth(&drawable, frame.leafMatrix, depth);
        }
    }
    if (state) _cv.popStateSet();
}

JointDrawBatch* ActorCull::openBatch(osgUtil::StateGraph* graph) const
{
    for (unsigned i = 0; i < _numOpen; ++i)
        if (_open[i].graph == graph) return _open[i].batch;
    return nullptr;
}

void ActorCull::closeBatch(osgUtil::StateGraph* graph)
{
    for (unsigned i = 0; i < _numOpen; ++i)
        if (_open[i].graph == graph)
        {
            _open[i] = _open[--_numOpen];
            return;
        }
}

void ActorCull::traverseOrdinarily(osg::Node& node, JointFrame& frame)
{
    _numOpen = 0; // the traversal may add leaves to any state graph: no batch may take drawables after them
    if (!frame.pushed)
    {
        if (!frame.leafMatrix) frame.leafMatrix = MatrixPool::createOrReuse(_cv, frame.modelView);
        _cv.pushModelViewMatrix(frame.leafMatrix, osg::Transform::RELATIVE_RF);
        frame.pushed = true;
    }
    node.accept(_cv);
}

bool ActorCull::isSmallFeature(const osg::BoundingSphere& bound, JointFrame& frame)
{
    if (!bound.valid()) return false; // the visitor never tests it (the node is not culling-active)
    if (!frame.hasPixelSizeVector)
    {
        // As osg::CullStack::pushCullingSet() makes it for this matrix.
        frame.pixelSizeVector = osg::CullingSet::computePixelSizeVector(*_cv.getViewport(),
                                                                        *_cv.getProjectionMatrix(), frame.modelView);
        frame.hasPixelSizeVector = true;
    }
    // osg::CullingSet::isCulled(const BoundingSphere&)'s small-feature test, term for term.
    return ((bound.center() * frame.pixelSizeVector) * _cv.getCurrentCullingSet().getSmallFeatureCullingPixelSize()) >
           bound.radius();
}

bool ActorCull::isOutsideFrustum(const osg::BoundingBox& box, const osg::Matrixd& modelView) const
{
    // The projection's culling set holds the frustum's planes in eye space; the visitor tests them moved into the
    // drawable's frame. A box is outside a plane when its farthest corner along the plane's normal is, that is
    // when all eight corners are, whichever frame they are taken in.
    osg::Vec3d corners[8];
    for (unsigned k = 0; k < 8; ++k) corners[k] = osg::Vec3d(box.corner(k)) * modelView;
    const osg::Polytope& frustum = _cv.getProjectionCullingStack().back().getFrustum();
    for (const osg::Plane& plane : frustum.getPlaneList())
    {
        bool allOutside = true;
        for (unsigned k = 0; k < 8 && allOutside; ++k) allOutside = plane.distance(corners[k]) < 0.0;
        if (allOutside) return true;
    }
    return false;
}

} // namespace detail
} // namespace osgActor
