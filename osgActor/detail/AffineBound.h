// Internal to the library (not installed, NOT API): osg::Transform::computeBound()'s result for the transforms an actor
// moves every frame, made cheaper. The actor's root joint translates, so its bound, and the actor's above it, are
// computed again at every frame: OSG's Transform::computeBound() asks the virtual computeLocalToWorldMatrix(), which
// multiplies the matrix by the identity, and moves four points by it, each with a projective division. For a
// MatrixTransform in a relative frame whose matrix is affine (its last column 0, 0, 0, 1, as every joint's and the
// actor's is) and a finite sphere, that division is by exactly 1 and the product with the identity changes no value:
// the same float arithmetic without them gives the same sphere (tests/nodes/test_affine_bound.cpp compares them).
#ifndef OSGACTOR_DETAIL_AFFINEBOUND_H
#define OSGACTOR_DETAIL_AFFINEBOUND_H 1

#include <osg/BoundingSphere>
#include <osg/MatrixTransform>

#include <cmath>

namespace osgActor {
namespace detail {

/** A point in a node's frame moved into its parent's by the node's affine matrix (OSG's row-vector order), each
  * coordinate summed in Matrixd::preMult(const Vec3f&)'s order. */
inline osg::Vec3f movedByAffine(const osg::Vec3f& v, const osg::Matrixd& m)
{
    return osg::Vec3f(static_cast<float>(m(0, 0) * v.x() + m(1, 0) * v.y() + m(2, 0) * v.z() + m(3, 0)),
                      static_cast<float>(m(0, 1) * v.x() + m(1, 1) * v.y() + m(2, 1) * v.z() + m(3, 1)),
                      static_cast<float>(m(0, 2) * v.x() + m(1, 2) * v.y() + m(2, 2) * v.z() + m(3, 2)));
}

/** Moves sphere (the children's, in the node's frame) into the parent's frame as osg::Transform::computeBound() does
  * for a relative frame whose local-to-world matrix is matrix: the centre moved, the radius the farthest of the
  * three points a radius off the centre along the axes, moved. false, the sphere untouched, where the matrix is not
  * affine or the sphere not finite: the caller then asks OSG. An invalid sphere stays as it is (true). */
inline bool moveBoundByAffine(osg::BoundingSphere& sphere, const osg::Matrixd& matrix)
{
    if (!sphere.valid()) return true;
    if (matrix(0, 3) != 0.0 || matrix(1, 3) != 0.0 || matrix(2, 3) != 0.0 || matrix(3, 3) != 1.0) return false;
    const osg::Vec3f centre = sphere.center();
    const float radius = sphere.radius();
    if (!std::isfinite(centre.x()) || !std::isfinite(centre.y()) || !std::isfinite(centre.z()) ||
        !std::isfinite(radius))
        return false;
    osg::Vec3f xdash = centre, ydash = centre, zdash = centre;
    xdash.x() += radius;
    ydash.y() += radius;
    zdash.z() += radius;
    const osg::Vec3f moved = movedByAffine(centre, matrix);
    const float lengthX = (movedByAffine(xdash, matrix) - moved).length();
    const float lengthY = (movedByAffine(ydash, matrix) - moved).length();
    const float lengthZ = (movedByAffine(zdash, matrix) - moved).length();
    float movedRadius = lengthX;
    if (movedRadius < lengthY) movedRadius = lengthY;
    if (movedRadius < lengthZ) movedRadius = lengthZ;
    sphere.set(moved, movedRadius);
    return true;
}

/** osg::MatrixTransform::computeBound() for a node whose class computes its local-to-world matrix as
  * osg::MatrixTransform does (the caller checks its class): the children's sphere (osg::Group's), moved by the
  * matrix here where it is affine, by OSG otherwise. */
inline osg::BoundingSphere matrixTransformBound(const osg::MatrixTransform& node)
{
    osg::BoundingSphere sphere = node.osg::Group::computeBound();
    if (moveBoundByAffine(sphere, node.getMatrix())) return sphere;
    return node.osg::MatrixTransform::computeBound();
}

} // namespace detail
} // namespace osgActor

#endif
