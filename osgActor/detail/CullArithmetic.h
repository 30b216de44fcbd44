// Internal to the library (not installed, NOT API): the cull visitor's arithmetic that the cull of an actor as one
// (ActorCull) and the instanced cull (InstancedCull) repeat without the visitor's stacks: a frame's model-view matrix,
// the small-feature test and the frustum test of a box, and the near and far distances of a box, each as the visitor
// computes it, so that both give the render graph the very bits, and drop the very drawables, the ordinary traversal
// does.
#ifndef OSGACTOR_DETAIL_CULLARITHMETIC_H
#define OSGACTOR_DETAIL_CULLARITHMETIC_H 1

#include <osg/BoundingBox>
#include <osg/BoundingSphere>
#include <osg/CullingSet>
#include <osg/Matrixd>
#include <osg/Polytope>
#include <osg/Viewport>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <utility>
#include <vector>

namespace osgActor {
namespace detail {

/** Whether the cull visitor's masks rule out a node of this mask (osg::NodeVisitor::validNodeMask()). */
inline bool isMaskedOut(unsigned traversalMask, unsigned nodeMaskOverride, unsigned nodeMask)
{
    return (traversalMask & (nodeMaskOverride | nodeMask)) == 0;
}

/** Whether two matrices hold the same bits: what the cull kept for one matrix holds for the other (a -0 is not a 0 to
  * the products made from it, and a NaN is the same NaN). */
inline bool sameBits(const osg::Matrixd& a, const osg::Matrixd& b)
{
    return std::memcmp(a.ptr(), b.ptr(), sizeof(osg::Matrixd)) == 0;
}

/** modelView = local * parent (OSG's row-vector order): what MatrixTransform::computeLocalToWorldMatrix() computes
  * for a relative frame, the call the visitor makes (osg::Matrixd::preMult), term for term and in the same order,
  * so the bits are the same; inline, into other memory than its inputs (so the compiler may take two columns at
  * once), and without preMult's temporary copy. Files that call it are compiled without contracting products and
  * sums into fused multiply-adds, as OSG is (osgActor/CMakeLists.txt). */
inline void composeModelView(const double* __restrict local, const double* __restrict parent,
                             double* __restrict modelView)
{
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col)
            modelView[row * 4 + col] = local[row * 4 + 0] * parent[0 * 4 + col] + local[row * 4 + 1] * parent[1 * 4 + col] +
                                       local[row * 4 + 2] * parent[2 * 4 + col] + local[row * 4 + 3] * parent[3 * 4 + col];
}

/** Whether the visitor would cull a sphere as a small feature in a frame whose pixel-size vector is given
  * (osg::CullingSet::computePixelSizeVector() of the frame's model-view matrix): osg::CullingSet::isCulled()'s test,
  * term for term. */
inline bool isSmallFeature(const osg::BoundingSphere& bound, const osg::Vec4& pixelSizeVector, float pixelSize)
{
    return ((bound.center() * pixelSizeVector) * pixelSize) > bound.radius();
}

/** The pixel-size vectors of an actor's frames (the actor's, then each planned joint's), each made the first time a
  * small-feature test in that frame needs it, as osg::CullStack::pushCullingSet() makes it for the frame's model-view
  * matrix. Kept from cull to cull, so that a steady frame allocates nothing. */
class FramePixelSizeVectors
{
public:
    /** Forgets every frame's vector, for numFrames frames. */
    void reset(std::size_t numFrames)
    {
        _known.assign(numFrames, 0);
        _vectors.resize(numFrames);
    }
    /** Gives a frame its vector (one the visitor computed already). */
    void set(std::size_t frame, const osg::Vec4& vector)
    {
        _vectors[frame] = vector;
        _known[frame] = 1;
    }
    /** isSmallFeature() in the frame whose model-view matrix is given; a bound that is not valid never is one (the
      * visitor never tests it: the node is not culling-active). */
    bool isSmallFeature(const osg::BoundingSphere& bound, std::size_t frame, const osg::Viewport& viewport,
                        const osg::Matrixd& projection, const osg::Matrixd& modelView, float pixelSize)
    {
        if (!bound.valid()) return false;
        return detail::isSmallFeature(bound, vector(frame, viewport, projection, modelView), pixelSize);
    }
    /** The frame's vector, made now if not known. */
    const osg::Vec4& vector(std::size_t frame, const osg::Viewport& viewport, const osg::Matrixd& projection,
                            const osg::Matrixd& modelView)
    {
        if (!_known[frame]) set(frame, osg::CullingSet::computePixelSizeVector(viewport, projection, modelView));
        return _vectors[frame];
    }

private:
    std::vector<osg::Vec4> _vectors;
    std::vector<unsigned char> _known;
};

/** Whether a local matrix moves by rotation and translation only, to within about 1e-9 (NaN fails): its upper 3x3
  * block's columns orthonormal (for a square block, as far as its rows are: R^T R and R R^T depart from the identity
  * by the same Frobenius norm), and its last column (0, 0, 0, 1). */
inline bool isRigid(const double* m)
{
    // Lane k: column k's squared length less 1, and its product with column (k + 1) mod 3; the last column's first
    // three entries, squared (0 in a rigid matrix). Summed without branches, so that the compiler may take the
    // columns two or four at once.
    static constexpr int kNext[3] = {1, 2, 0};
    double deviation = m[3] * m[3] + m[7] * m[7] + m[11] * m[11] + (m[15] - 1.0) * (m[15] - 1.0);
    for (int k = 0; k < 3; ++k)
    {
        const double column = m[k] * m[k] + m[4 + k] * m[4 + k] + m[8 + k] * m[8 + k] - 1.0;
        const double across = m[k] * m[kNext[k]] + m[4 + k] * m[4 + kNext[k]] + m[8 + k] * m[8 + kNext[k]];
        deviation += column * column + across * across;
    }
    return deviation < 1e-18;
}

/** How far a rigid local matrix moves its frame's origin, at most: its translation's absolute components, summed
  * (parent frame units). */
inline double translationReach(const double* m) { return std::abs(m[12]) + std::abs(m[13]) + std::abs(m[14]); }

/** What the small-feature proof needs of the joints of a subtree in an actor's own frame: whether every joint's
  * local matrix is rigid (isRigid()), and how far the joints' origins can be from the actor's origin (actor frame
  * units, the frames rigid: the largest sum of translationReach() on the way down). Kept by each skeleton node for its
  * subtree as its bound is computed (SkeletonNode::computeBound(), detail::SkeletonNodeAccess::subtreeShape()), so
  * that a cull reads it at the top joints instead of every joint's matrix. */
struct SubtreeShape
{
    bool rigid;
    double reach;
};

/** A proof, for the subtree of a joint in an actor's own frame, that the cull visitor would find no small feature in
  * it, so that its joints' and geodes' spheres need not be read nor tested (most of a moving crowd's tests; each
  * would read a joint's bound and make its frame's pixel-size vector).
  *
  * Where every joint's local matrix in the subtree is rigid, every frame below the actor's has the actor frame's
  * pixel-size vector, moved: for a point, the product with its frame's vector (its eye-space w times a factor that
  * only a scale would change) is the product of the same point, taken in the actor's frame, with the actor frame's
  * vector. The spheres below the joint lie in the joint's own sphere (each bound holds its children's), so none is
  * tested larger than that product's largest value over the joint's sphere; and none is smaller than the smallest
  * geode's below it, when every joint below has a geode below it. When that largest value times the pixel size is
  * below that radius by more than a bound on the rounding (the vectors and the bounds are floats, made in other
  * frames than this product), no test below can find a small feature. Otherwise the exact tests run. */
struct SmallFeatureProof
{
    /** Whether no sphere below a joint of the actor's frame is a small feature: top is the joint's sphere (actor's
      * frame), shape its subtree's, actorVector the actor frame's pixel-size vector, smallestRadius
      * ActorCullPlan::smallestGeodeRadiusBelow()'s. */
    static bool holds(const osg::BoundingSphere& top, const SubtreeShape& shape, const osg::Vec4& actorVector,
                      float pixelSize, double smallestRadius)
    {
        if (!shape.rigid || !top.valid() || !(pixelSize > 0.0f)) return false;
        const double gradient = osg::Vec3d(actorVector.x(), actorVector.y(), actorVector.z()).length();
        const osg::Vec3d centre(top.center());
        const double extent = centre.length() + top.radius() + 2.0 * shape.reach; // coordinates in any frame below
        const double tolerance = kRelativeTolerance * extent;  // each bound's containment of its children's
        const double largest =
            centre * osg::Vec3d(actorVector.x(), actorVector.y(), actorVector.z()) + actorVector.w() +
            gradient * (top.radius() + tolerance);
        const double rounding = kRelativeTolerance * (gradient * (extent + tolerance) + std::abs(actorVector.w()));
        return (largest + rounding) * pixelSize * (1.0 + kRelativeTolerance) < smallestRadius - tolerance;
    }

    /** A relative bound on the rounding, far above what floats and doubles accumulate over any skeleton's depth,
      * so that only spheres within this share of the threshold are tested exactly. */
    static constexpr double kRelativeTolerance = 1e-4;
};

/** Whether a box in a frame lies wholly outside one plane of a frustum given in eye space (the projection's culling
  * set's). The visitor tests the planes moved into the box's frame; a box is outside a plane when its farthest corner
  * along the plane's normal is, that is when all eight corners are, whichever frame they are taken in. */
inline bool isOutsideFrustum(const osg::BoundingBox& box, const osg::Matrixd& modelView, const osg::Polytope& frustum)
{
    osg::Vec3d corners[8];
    for (unsigned k = 0; k < 8; ++k) corners[k] = osg::Vec3d(box.corner(k)) * modelView;
    for (const osg::Plane& plane : frustum.getPlaneList())
    {
        bool allOutside = true;
        for (unsigned k = 0; k < 8 && allOutside; ++k) allOutside = plane.distance(corners[k]) < 0.0;
        if (allOutside) return true;
    }
    return false;
}

/** Whether a sphere lies wholly inside every plane (osg::Plane::intersect(), the visitor's test of a node's sphere,
  * for planes in the sphere's frame); a sphere that is not valid never does (the visitor does not test it). */
inline bool isWhollyInside(const osg::BoundingSphere& bound, const std::vector<osg::Plane>& planes)
{
    if (!bound.valid()) return false;
    for (const osg::Plane& plane : planes)
        if (plane.intersect(bound) <= 0) return false;
    return true;
}

/** A point's distance in front of the eye along the view, in the cull visitor's arithmetic for its near and far
  * planes (doubles: CullVisitor::value_type): minus the eye-space z. eyeDepth() is the same, rounded to a float for
  * depth sorting. */
inline double eyeDistance(const osg::Vec3& point, const osg::Matrixd& modelView)
{
    return -(static_cast<double>(point[0]) * modelView(0, 2) + static_cast<double>(point[1]) * modelView(1, 2) +
             static_cast<double>(point[2]) * modelView(2, 2) + modelView(3, 2));
}

/** The near and far distances that drawables' boxes give the cull visitor computing its near and far planes from
  * bounding volumes (osg::CullSettings::COMPUTE_NEAR_FAR_USING_BOUNDING_VOLUMES), gathered as it gathers them: the
  * least near and the greatest far, each taken where it is less (greater) than the one so far, so that gathering an
  * actor's drawables here and then merging the result into the visitor (mergeInto()) gives the visitor's values of
  * taking them one by one, to the bit. Empty, it changes nothing. */
struct DepthRange
{
    double nearest = std::numeric_limits<double>::infinity();
    double farthest = -std::numeric_limits<double>::infinity();

    /** What CullVisitor::updateCalculatedNearFar(modelView, drawable, true) does for a drawable of this box (valid)
      * in a frame of this model-view matrix, with its arithmetic: the box's corners nearest and farthest along the
      * view (chosen by the signs of the look vector, in floats as the visitor takes it), their distances, and false,
      * the range unchanged, where the whole box is behind the eye (the visitor then drops the drawable). */
    bool addBox(const osg::BoundingBox& box, const osg::Matrixd& modelView)
    {
        const osg::Vec3 look(-modelView(0, 2), -modelView(1, 2), -modelView(2, 2));
        const unsigned farCorner = (look.x() >= 0 ? 1u : 0u) + (look.y() >= 0 ? 2u : 0u) + (look.z() >= 0 ? 4u : 0u);
        const unsigned nearCorner = ~farCorner & 7u;
        double nearDistance = eyeDistance(box.corner(nearCorner), modelView);
        double farDistance = eyeDistance(box.corner(farCorner), modelView);
        if (nearDistance > farDistance) std::swap(nearDistance, farDistance);
        if (farDistance < 0.0) return false;
        if (nearDistance < nearest) nearest = nearDistance;
        if (farDistance > farthest) farthest = farDistance;
        return true;
    }
    /** Into the visitor's computed near and far, as each drawable gathered would have gone. */
    template <class Visitor>
    void mergeInto(Visitor& cv) const
    {
        if (nearest < cv.getCalculatedNearPlane()) cv.setCalculatedNearPlane(nearest);
        if (farthest > cv.getCalculatedFarPlane()) cv.setCalculatedFarPlane(farthest);
    }
};

} // namespace detail
} // namespace osgActor

#endif
