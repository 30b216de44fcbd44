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

namespace osgActor {
namespace detail {

/** Moves sphere (the children's, in the node's frame) into the parent's frame as osg::Transform::computeBound() does
  * for a relative frame whose local-to-world matrix is matrix: the centre moved, the radius the farthest of the
  * three points a radius off the centre along the axes, moved (each coordinate summed in
  * Matrixd::preMult(const Vec3f&)'s order, rounded to float, the distances in float). false, the sphere untouched,
  * where the matrix is not affine or the sphere not finite: the caller then asks OSG. An invalid sphere stays as it
  * is (true). (AffineBound.cpp) */
bool moveBoundByAffine(osg::BoundingSphere& sphere, const osg::Matrixd& matrix);

/** osg::MatrixTransform::computeBound() for a node whose class computes its local-to-world matrix as
  * osg::MatrixTransform does (the caller checks its class), given its children's sphere as osg::Group computes it
  * (detail::childrenBound()): that sphere moved by the matrix here where it is affine, by OSG otherwise. */
inline osg::BoundingSphere matrixTransformBound(const osg::MatrixTransform& node, osg::BoundingSphere childrenSphere)
{
    if (moveBoundByAffine(childrenSphere, node.getMatrix())) return childrenSphere;
    return node.osg::MatrixTransform::computeBound();
}

} // namespace detail
} // namespace osgActor

#endif
