/* osgActor: the osg::Geometry objects SkinnedMesh draws, built from a skin and a surface. Internal to the library. */
#ifndef OSGACTOR_SKINNEDMESHGEOMETRY_H
#define OSGACTOR_SKINNEDMESHGEOMETRY_H 1

#include <osgActor/SkinningShaders>
#include <osgActor/core/skin/Skin>

#include <osg/Geometry>

#include <string>

namespace osgActor {

/** The influences per vertex a skin's shaders read: 4, or 8 when a vertex has more than 4. */
unsigned shaderInfluences(const Skin& skin);

/** Why the skin and the surface cannot make a mesh (an index beyond the skin's vertices, a per-vertex array of
  * another size, a vertex or normal array on the surface), or empty. */
std::string checkSkinnedSurface(const Skin& skin, const osg::Geometry& surface);

/** The skin's bind pose in the file's order and its influences, as the GPU path reads them: positions and normals
  * (bind space, model units), and the vertex attributes osgActor_joints (joint indices as floats; with 8 influences
  * two per component, first + 4096 x second), osgActor_weights and, with 8 influences, osgActor_weights1 (a vertex's
  * unused influences have weight 0). One static vertex buffer object holds them all. */
struct SkinVertexArrays
{
    osg::ref_ptr<osg::Vec3Array> positions;
    osg::ref_ptr<osg::Vec3Array> normals; // null without normals
    osg::ref_ptr<osg::Vec4Array> joints;
    osg::ref_ptr<osg::Vec4Array> weights;
    osg::ref_ptr<osg::Vec4Array> weights1; // null with 4 influences
};
SkinVertexArrays makeSkinVertexArrays(const Skin& skin);

/** The geometry the GPU path draws in a profile: the arrays in their slots (skinAttributeSlots(profile)) and the
  * surface's per-vertex arrays and primitive sets, shared. */
osg::ref_ptr<osg::Geometry> makeBindPoseGeometry(const SkinVertexArrays& arrays, const osg::Geometry& surface,
                                                 SkinningProfile profile);

/** A geometry the CPU path writes into: new position and normal arrays (model space) in a buffer object of their
  * own, with the bind-pose geometry's per-vertex arrays and primitive sets shared, and no influence attribute. */
osg::ref_ptr<osg::Geometry> makeSkinnedOutputGeometry(const osg::Geometry& bindPose);

} // namespace osgActor

#endif
