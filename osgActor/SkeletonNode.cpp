#include <osgActor/SkeletonNode>
#include <osgActor/ActorNode>
#include <osgActor/detail/AffineBound.h>
#include <osgActor/detail/ChildrenBound.h>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/PlacedSkeletonNode.h>
#include <osgActor/detail/SkeletonNodeAccess.h>
#include <osgActor/core/detail/HotPath.h>

#include <osgUtil/IntersectionVisitor>

#include <algorithm>
#include <cmath>
#include <typeinfo>

namespace osgActor {

SkeletonNode::SkeletonNode()
    : _jointIndex(0), _hidden(false), _boundCoversRotations(false), _ballOffCentre(false), _subtreeRigid(false),
      _reachBelow(0.0)
{
    // The matrix changes from frame to frame: keep osgUtil::Optimizer from flattening it away.
    setDataVariance(osg::Object::DYNAMIC);
}

SkeletonNode::SkeletonNode(unsigned jointIndex, const std::string& jointName) : SkeletonNode()
{
    _jointIndex = jointIndex;
    setName(jointName);
}

SkeletonNode::SkeletonNode(const SkeletonNode& node, const osg::CopyOp& copyop)
    : osg::MatrixTransform(node, copyop), _jointIndex(node._jointIndex), _hidden(node._hidden),
      _boundCoversRotations(node._boundCoversRotations), _ballOffCentre(node._ballOffCentre),
      _jointCentre(node._jointCentre), _subtreeRigid(node._subtreeRigid), _reachBelow(node._reachBelow)
{
}

void SkeletonNode::setHidden(bool hidden)
{
    if (hidden == _hidden) return;
    _hidden = hidden;
    dirtyActorCullPlans();
}

bool SkeletonNode::reportEdit(bool edited)
{
    if (edited) dirtyActorCullPlans();
    return edited;
}

bool SkeletonNode::addChild(osg::Node* child) { return reportEdit(osg::MatrixTransform::addChild(child)); }

bool SkeletonNode::insertChild(unsigned int index, osg::Node* child)
{
    return reportEdit(osg::MatrixTransform::insertChild(index, child));
}

bool SkeletonNode::removeChildren(unsigned int pos, unsigned int numChildrenToRemove)
{
    return reportEdit(osg::MatrixTransform::removeChildren(pos, numChildrenToRemove));
}

bool SkeletonNode::setChild(unsigned int i, osg::Node* node)
{
    return reportEdit(osg::MatrixTransform::setChild(i, node));
}

void SkeletonNode::dirtyActorCullPlans()
{
    for (osg::Group* parent : _parents)
    {
        if (ActorNode* actor = dynamic_cast<ActorNode*>(parent)) actor->dirtyCullPlan();
        else if (SkeletonNode* joint = dynamic_cast<SkeletonNode*>(parent)) joint->dirtyActorCullPlans();
    }
}

void SkeletonNode::traverse(osg::NodeVisitor& nv)
{
    if (_hidden && (nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR ||
                    dynamic_cast<osgUtil::IntersectionVisitor*>(&nv) != nullptr))
        return;
    osg::MatrixTransform::traverse(nv);
}

namespace {

// Built for x86-64-v3 too: where the bounds follow the pose, every moving joint computes its bound, and so this, at
// every frame.
OSGACTOR_HOT_PATH bool isRigidMatrix(const double* m) { return detail::isRigid(m); }

} // namespace

osg::BoundingSphere SkeletonNode::computeBound() const
{
    if (!_boundCoversRotations || _referenceFrame != RELATIVE_RF)
    {
        // A joint that translates (the root, mostly) computes this at every frame: without OSG's generic steps
        // where the class computes its matrix as osg::MatrixTransform does (a subclass may not). The type's identity
        // by address: type_info's comparison compares the names of two different types, and a type told apart
        // wrongly only takes OSG's way.
        const std::type_info* const type = &typeid(*this);
        const bool plainClass = type == &typeid(SkeletonNode) || type == &typeid(detail::PlacedSkeletonNode);
        if (!plainClass)
        {
            const osg::BoundingSphere bound = osg::MatrixTransform::computeBound();
            noteSubtreeShape(isRigidMatrix(_matrix.ptr()));
            return bound;
        }
        // The subtree's shape noted in the union's one visit of the children, each child transform's after its bound
        // is computed (as noteSubtreeShape() does).
        bool subtreeRigid = isRigidMatrix(_matrix.ptr());
        double reachBelow = 0.0;
        const osg::BoundingSphere children = detail::childrenBound(_children, [&](const osg::Transform& transform) {
            detail::SkeletonNodeAccess::noteChildShape(transform, subtreeRigid, reachBelow);
        });
        _subtreeRigid = subtreeRigid;
        _reachBelow = reachBelow;
        return detail::matrixTransformBound(*this, children);
    }
    // The joint turns about its own origin, so a ball about that origin that holds every child's bound holds it in
    // any rotation: its radius is the farthest reach of a child's sphere. Children are taken as osg::Group takes
    // them: those with an absolute reference frame, and empty ones, do not count. The subtree's shape is noted in
    // the same visit, while the child is in cache: a wide joint's children do not stay there for a second pass.
    double reach = -1.0;
    const bool rigid = isRigidMatrix(_matrix.ptr());
    bool subtreeRigid = rigid;
    double reachBelow = 0.0;
    for (const osg::ref_ptr<osg::Node>& child : _children)
    {
        const osg::Transform* transform = child->asTransform();
        if (transform && transform->getReferenceFrame() != RELATIVE_RF) continue;
        const osg::BoundingSphere& bound = child->getBound();
        if (bound.valid()) reach = std::max(reach, osg::Vec3d(bound.center()).length() + bound.radius());
        if (transform) detail::SkeletonNodeAccess::noteChildShape(*transform, subtreeRigid, reachBelow);
    }
    _subtreeRigid = subtreeRigid;
    _reachBelow = reachBelow;
    // About the centre the matrix shows; if that is not the joint's (a matrix set by hand), the actor's next
    // write, which puts it back, must make a new ball; so too where the matrix is not rigid (a scale set by hand),
    // which the actor's write makes rigid again: the ball shrinks back, and the subtree's shape is noted anew.
    const osg::Vec3d centre = _matrix.getTrans();
    _ballOffCentre = centre != _jointCentre || !rigid;
    if (reach < 0.0) return osg::BoundingSphere();
    // The actor writes rigid matrices; a scale a user set with setMatrix() widens the ball as it would widen
    // osg::Transform's bound (the longest image of a unit axis).
    double scale2 = 0.0;
    for (int row = 0; row < 3; ++row)
        scale2 = std::max(scale2, _matrix(row, 0) * _matrix(row, 0) + _matrix(row, 1) * _matrix(row, 1) +
                                      _matrix(row, 2) * _matrix(row, 2));
    return osg::BoundingSphere(centre, reach * std::sqrt(scale2));
}

void SkeletonNode::noteSubtreeShape(bool rigid) const
{
    // The bounds of the relative children are computed: a child skeleton node's shape is as of that computation,
    // unless a callback computed its bound instead of computeBound(). Only the classes an actor's cull plans count
    // (exactly these: a subclass, and all below it, is traversed ordinarily); a type's identity, not a dynamic_cast,
    // since a joint that translates computes its bound, and so this, at every frame.
    double reach = 0.0;
    for (const osg::ref_ptr<osg::Node>& child : _children)
    {
        // Transforms first (geodes, most children, answer at once).
        if (const osg::Transform* transform = child->asTransform())
            detail::SkeletonNodeAccess::noteChildShape(*transform, rigid, reach);
    }
    _subtreeRigid = rigid;
    _reachBelow = reach;
}

} // namespace osgActor
