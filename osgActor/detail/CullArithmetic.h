// Internal to the library (not installed, NOT API): the cull visitor's arithmetic that the cull of an actor as one
// (ActorCull) and the instanced cull (InstancedCull) repeat without the visitor's stacks: a frame's model-view matrix,
// the small-feature test and the frustum test of a box, each as the visitor computes it, so that both give the render
// graph the very bits, and drop the very drawables, the ordinary traversal does.
#ifndef OSGACTOR_DETAIL_CULLARITHMETIC_H
#define OSGACTOR_DETAIL_CULLARITHMETIC_H 1

#include <osg/BoundingBox>
#include <osg/BoundingSphere>
#include <osg/CullingSet>
#include <osg/Matrixd>
#include <osg/Polytope>
#include <osg/Viewport>

#include <cstddef>
#include <vector>

namespace osgActor {
namespace detail {

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
        if (!_known[frame]) set(frame, osg::CullingSet::computePixelSizeVector(viewport, projection, modelView));
        return detail::isSmallFeature(bound, _vectors[frame], pixelSize);
    }

private:
    std::vector<osg::Vec4> _vectors;
    std::vector<unsigned char> _known;
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

} // namespace detail
} // namespace osgActor

#endif
