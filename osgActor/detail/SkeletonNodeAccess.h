// Internal to the library (not installed, NOT API): what an ActorNode does to its own skeleton nodes each frame.
// The local-matrices job writes each changed joint's skl_m straight into its node's matrix; the actor then sets the
// node's flags here, without osg::Transform's walk up the parents: the actor dirties its own nodes first and then
// itself, so that the part touching only this actor's nodes can run on a worker thread (ActorGroup). A friend of
// SkeletonNode, so that none of this is in the installed header.
#ifndef OSGACTOR_DETAIL_SKELETONNODEACCESS_H
#define OSGACTOR_DETAIL_SKELETONNODEACCESS_H 1

#include <osgActor/SkeletonNode>
#include <osgActor/detail/CullArithmetic.h>
#include <osgActor/detail/PlacedSkeletonNode.h>

#include <algorithm>
#include <typeinfo>

namespace osgActor {
namespace detail {

struct SkeletonNodeAccess
{
    /** The node's matrix as 16 doubles in OSG's (and GLM's) memory order: where the local-matrices job writes the
      * joint's skl_m. */
    static double* matrixStorage(SkeletonNode& node) { return node._matrix.ptr(); }

    /** Makes room for the node's children before they are added: adding them one by one would grow the list by
      * copying it, and each copy of an osg::ref_ptr touches the child it points to. */
    static void reserveChildren(SkeletonNode& node, unsigned numChildren) { node._children.reserve(numChildren); }

    /** Puts child, a skeleton node just made (no parent, no child, no callback, culling on, not an osg::OccluderNode),
      * at the end of parent's children: what osg::Group::insertChild() does for such a child, whose counts of
      * children needing update or event traversals, with culling disabled or with occluders it would leave as they
      * are, and which no other thread can see yet. Group::insertChild() finds that out by asking the child, its
      * occluders by a dynamic_cast that walks the class's bases, comparing names: as much work as the rest of the
      * node's making. A node in any other state is added by insertChild() as usual. */
    static void appendNewChild(SkeletonNode& parent, SkeletonNode& child)
    {
        if (!child._parents.empty() || !child._children.empty() || child.getUpdateCallback() ||
            child.getNumChildrenRequiringUpdateTraversal() > 0 || child.getEventCallback() ||
            child.getNumChildrenRequiringEventTraversal() > 0 || !child.getCullingActive() ||
            child.getNumChildrenWithCullingDisabled() > 0 || child.getNumChildrenWithOccluderNodes() > 0 ||
            typeid(child) != typeid(PlacedSkeletonNode))
        {
            parent.osg::Group::insertChild(parent.getNumChildren(), &child);
            return;
        }
        parent._children.push_back(&child);
        child._parents.push_back(&parent);
        parent.childInserted(static_cast<unsigned>(parent._children.size() - 1));
        parent.dirtyBound();
    }

    /** Marks the node's bound dirty without walking to the parents; returns whether it had been computed (false:
      * it, and so its ancestors', were dirty already). */
    static bool markBoundDirty(SkeletonNode& node)
    {
        const bool wasComputed = node._boundingSphereComputed;
        if (wasComputed) node._boundingSphereComputed = false;
        return wasComputed;
    }

    /** The job wrote the node's matrix in place: dirties its inverse and its bound (not the parents'). Returns
      * whether the bound had been computed. */
    static bool matrixWritten(SkeletonNode& node)
    {
        markInverseDirty(node);
        return markBoundDirty(node);
    }

    /** The same for a node whose bound covers its rotations (the caller checked getBoundCoversRotations()), with a
      * matrix that keeps the joint's centre where it is: the bound is dirtied only if the ball was made about
      * another centre (the node then showed a matrix set by hand with setMatrix(), or read from a file), so the
      * cache line that holds the bound's flag is normally not touched at all. Returns whether it dirtied the
      * bound. */
    static bool matrixWrittenKeepingBall(SkeletonNode& node)
    {
        markInverseDirty(node);
        if (!node._ballOffCentre) return false;
        node._ballOffCentre = false;
        return markBoundDirty(node);
    }

    /** Asks the processor to fetch what the job and matrixWritten() write, ahead of the writes: with many actors
      * the nodes fall out of cache between frames, and the fetches then overlap the pose's computation. Into L2
      * rather than L1 (locality 2), since an actor's nodes need more lines than L1 has fill buffers for; the matrix
      * may span three cache lines. boundToo: also the line that holds the bound's flag, which a node whose bound
      * covers its rotations does not touch (the caller knows which, without reading the node). */
    static void prefetchForMatrixWrite(const SkeletonNode& node, bool boundToo)
    {
#if defined(__GNUC__)
        const double* matrix = node._matrix.ptr();
        __builtin_prefetch(matrix, 1, 2);
        __builtin_prefetch(matrix + 8, 1, 2);
        __builtin_prefetch(matrix + 15, 1, 2);
        __builtin_prefetch(&node._inverseDirty, 0, 2);
        if (boundToo) __builtin_prefetch(&node._boundingSphereComputed, 0, 2);
#else
        (void)node;
        (void)boundToo;
#endif
    }

    /** The shape of the node's subtree for the small-feature proof (SkeletonNode::_subtreeRigid, its reach from
      * the node's parent's origin), as of the bound's computation, which this makes if it is due: where a callback
      * computes the bound instead of computeBound(), not known, so not rigid. */
    static SubtreeShape subtreeShape(const SkeletonNode& node)
    {
        node.getBound();
        return {node._subtreeRigid && !node.getComputeBoundingSphereCallback(),
                translationReach(node._matrix.ptr()) + node._reachBelow};
    }

    /** Adds a child's subtree to a shape being noted (SkeletonNode::_subtreeRigid and _reachBelow of its parent):
      * a skeleton node of the classes an actor's cull plans, in its parent's frame, whose bound is computed; other
      * children add nothing. */
    static void noteChildShape(const osg::Transform& child, bool& rigid, double& reach)
    {
        // The classes first; a type that is not the one compared with is told by its name.
        const std::type_info& type = typeid(child);
        if (type != typeid(PlacedSkeletonNode) && type != typeid(SkeletonNode)) return;
        const SkeletonNode& joint = static_cast<const SkeletonNode&>(child);
        if (joint._referenceFrame != osg::Transform::RELATIVE_RF) return;
        rigid = rigid && joint._subtreeRigid && !joint.getComputeBoundingSphereCallback();
        reach = std::max(reach, translationReach(joint._matrix.ptr()) + joint._reachBelow);
    }

private:
    static void markInverseDirty(SkeletonNode& node)
    {
        // Stored only when it changes: with a thousand actors the nodes fall out of cache between frames, and a
        // cache line only read is cheaper to evict than one written.
        if (!node._inverseDirty) node._inverseDirty = true;
    }
};

} // namespace detail
} // namespace osgActor

#endif
