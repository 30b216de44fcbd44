// Internal to the library (not installed, NOT API): the skinned half of the instanced cull (InstancedCull, issue 28),
// NVIDIA's "skinned instancing". A SkinnedMesh that several actors share (clones share their geodes) is drawn with
// one instanced draw of its bind-pose geometry for every actor that sees it this frame; each instance's data in the
// frame's texture buffer is its model-view matrix (4 texels) and then its palette, the rows the GPU path lays out
// (SkinPalette.h's writeSkinPaletteRows()) from the skinning matrices the mesh's update (or the actor's worker,
// PoseFollower) computed: nothing is computed a second way. The vertex shader is SkinnedMesh.vert's
// SkinInstancing::PerInstance variant.
//
// What an instanced actor's mesh must be, else the whole actor is drawn ordinarily: a SkinnedMesh of that exact class
// in the actor's own frame (below it, or in a geode below it), with no cull callback, that can draw (set up, its
// skin bound to the actor's definition), drawn on the GPU path for that actor (linear blend, 4 or 8 influences, or
// dual quaternions, whose bind scale, the skin's, is set per draw), in either profile, of a bind-pose geometry
// InstancedDraw can draw.
#ifndef OSGACTOR_DETAIL_INSTANCEDSKIN_H
#define OSGACTOR_DETAIL_INSTANCEDSKIN_H 1

#include <osgActor/SkinningShaders>
#include <osgActor/detail/ActorCullPlan.h>

#include <osg/Geometry>
#include <osg/Matrixd>
#include <osg/StateSet>

namespace osgActor {

class ActorNode;
class SkinnedMesh;
class SkinnedMeshInstance;

namespace detail {

class InstancedSkin
{
public:
    /** The mesh of a plan's step when it is one the instanced cull may take (an ORDINARY step of exactly a SkinnedMesh
      * in the actor's frame; its cull callback, state set and mask, which the plan does not watch, are the cull's to
      * check); null otherwise. */
    static SkinnedMesh* meshOfStep(const ActorCullPlan::Step& step);

    /** Texels per instance of the mesh drawn instanced (its matrix and its palette), or 0 when the mesh cannot be
      * (setup error, a skin the GPU path does not draw, a bind-pose geometry InstancedDraw does not draw); from what
      * the mesh is now, so asked once per cull. */
    static unsigned texelsPerInstance(SkinnedMesh& mesh);

    /** The skin's bind scale, which a dual-quaternion mesh's program reads (osgActor_bindScale) as the ordinary path's
      * palette state sets it; 1 for linear blend. */
    static float bindScaleOf(const SkinnedMesh& mesh);

    /** Whether the state set (the mesh's or its geode's) lets its instances be drawn together: no render bin of its
      * own (a bin sorted by depth would sort instances one draw holds), and nothing on the instances' texture unit. */
    static bool isInstanceableState(const osg::StateSet* state);

    /** The actor's state in the mesh when the mesh draws it on the GPU path (made on first use, as the mesh's own cull
      * makes it), or null when the actor must be drawn ordinarily (its skin not bound, the CPU path). */
    static const SkinnedMeshInstance* instanceOf(SkinnedMesh& mesh, ActorNode& actor);

    /** Whether the instance has skinning matrices yet (the mesh draws nothing for the actor before its first update)
      * and its bound (model space) for the cull. */
    static bool hasMatrices(const SkinnedMeshInstance& instance);
    static const osg::BoundingBox& boundOf(const SkinnedMeshInstance& instance);

    /** Writes one instance's data at out: the model-view matrix (16 floats, OSG's rows, each double rounded to the
      * nearest float as glLoadMatrixd keeps it) and the palette rows of the mesh's program variant (the same layout in
      * either profile). */
    static void writeInstance(const SkinnedMesh& mesh, const SkinnedMeshInstance& instance, const osg::Matrixd& modelView,
                              float* out);

    /** The program key of the mesh's instanced draws in the profile (lights and the rest of the state in effect set
      * by the caller as the mesh's cull sets them). */
    static SkinningProgramKey programKey(const SkinnedMesh& mesh, SkinningProfile profile);

    /** The geometry the instanced draw draws: the mesh's bind-pose geometry of the profile, whose box is the union of
      * its actors' bounds, as the ordinary cull hands it to the visitor. */
    static osg::Geometry* geometryOf(SkinnedMesh& mesh, SkinningProfile profile);
};

} // namespace detail
} // namespace osgActor

#endif
