// Internal to the library (not installed, NOT API): the cull traversal of one actor as one (issue 28).
//
// osgUtil::CullVisitor, walking an actor node by node, pushes and pops a model-view matrix and a culling set (its
// frustum's planes transformed into the node's frame) at every skeleton node and tests every node's, geode's and
// drawable's bound against them: most of a crowd's frame. The visitor has already tested the actor's bound once,
// on its way into the actor, and pushed actor_m; ActorCull then goes through the actor's subtree itself, in the
// order the visitor would, and:
//  - at a "plain" skeleton node (an osgActor::SkeletonNode of its own class, no cull callback, not hidden, a
//    relative reference frame, a node mask the visitor accepts) computes the joint's model-view matrix in eye
//    space with the very call the visitor makes (MatrixTransform::computeLocalToWorldMatrix, so the bits are the
//    same) and pushes no matrix and no culling set;
//  - hands a plain geode's plain drawables (an osg::Geode and drawables without cull callbacks) straight to the
//    render graph (CullVisitor::addDrawableAndDepth) with that matrix and the depth the visitor computes; state
//    sets on the joint, the geode or the drawable are pushed as the visitor pushes them (pushStateSet), so the
//    drawables land in the same state graphs and render bins;
//  - gives everything else (cull callbacks, hidden joints, LOD and switch nodes, a user's nodes, other classes)
//    the ordinary traversal, with the joint's model-view matrix pushed first, so it sees what it would see below
//    the joint.
// What may change the image is culled as the visitor culls it: small features (the same pixel-size test with the
// same pixel-size vector), and, while the visitor computes near and far planes from what it draws, each drawable's
// box against the frustum (in eye space: all eight corners outside one plane, the visitor's test, in another frame)
// before it counts for near and far. What only saves work is skipped: spheres against the frustum, so a drawable
// outside the view may reach the render graph, where OpenGL clips it, and the statistics count it.
#ifndef OSGACTOR_DETAIL_ACTORCULL_H
#define OSGACTOR_DETAIL_ACTORCULL_H 1

#include <osgActor/SkeletonNode>
#include <osgActor/detail/JointDrawBatch.h>

#include <osg/Geode>
#include <osgUtil/CullVisitor>

namespace osgActor {
namespace detail {

class ActorCull
{
public:
    /** Whether the visitor can take the actor as one: its own class (a subclass may draw otherwise), and no
      * occluders or state frustums in the current culling set (they need each drawable's box in its own frame). */
    static bool canCullAsOne(osgUtil::CullVisitor& cv);

    explicit ActorCull(osgUtil::CullVisitor& cv);

    /** Culls the children of the actor node the visitor is in now (its model-view matrix on top of the stack). */
    void cullChildren(osg::Group& actor);

private:
    /** A joint's eye-space frame as the walk through the actor holds it. */
    struct JointFrame
    {
        osg::Matrixd modelView;           // the joint's frame to eye space (OSG's row-vector order)
        osg::RefMatrix* leafMatrix;       // modelView in the visitor's pool, made at the first drawable; or null
        osg::Vec4 pixelSizeVector;        // the culling set's, for modelView; valid when hasPixelSizeVector
        bool hasPixelSizeVector;
        bool pushed;                      // modelView is on the visitor's stacks (the actor's own frame always is)
    };

    void cullChild(osg::Node& child, JointFrame& frame);
    void cullJoint(SkeletonNode& joint, JointFrame& parent);
    void cullGeode(osg::Geode& geode, JointFrame& frame);
    void addDrawable(osg::Drawable& drawable, JointFrame& frame);
    /** The ordinary traversal of a node below the joint, with the joint's frame pushed as the visitor would. */
    void traverseOrdinarily(osg::Node& node, JointFrame& frame);
    /** Whether the visitor would cull a sphere in the joint's frame as a small feature. */
    bool isSmallFeature(const osg::BoundingSphere& bound, JointFrame& frame);
    /** Whether a box in the joint's frame lies wholly outside one plane of the view frustum. */
    bool isOutsideFrustum(const osg::BoundingBox& box, const osg::Matrixd& modelView) const;
    static bool isPlainJoint(const SkeletonNode& joint);
    /** No cull callback: the visitor would do nothing else at the node than push its state set. */
    static bool isPlain(const osg::Node& node) { return !node.getCullCallback(); }
    /** A drawable the visitor would only add to the render graph: no cull callback, and of a class known not to cull
      * in its own way (a subclass such as SkinnedMesh overrides accept() to skin or upload before it is drawn). */
    static bool isPlainDrawable(const osg::Drawable& drawable);

    /** The batch open for the current state graph, or null. */
    JointDrawBatch* openBatch(osgUtil::StateGraph* graph) const;
    void closeBatch(osgUtil::StateGraph* graph);

    osgUtil::CullVisitor& _cv;
    bool _smallFeatureCulling;
    bool _computeNearFar;
    bool _frustumCulling;
    /** The batches this actor is filling, by state graph: a drawable goes into its graph's open batch, which is
      * closed when anything else may land in that graph (a drawable that is not batched, an ordinary traversal),
      * so the graph's leaves keep the order the ordinary traversal gives them. */
    struct OpenBatch
    {
        osgUtil::StateGraph* graph;
        JointDrawBatch* batch;
    };
    static constexpr unsigned kMaxOpenBatches = 8;
    OpenBatch _open[kMaxOpenBatches];
    unsigned _numOpen;
};

} // namespace detail
} // namespace osgActor

#endif
