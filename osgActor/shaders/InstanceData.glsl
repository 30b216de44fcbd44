// The per-instance data of osgActor's instanced draws (InstancedActorGroup, docs/architecture.md), before the vertex
// shader that reads it (InstancedRigid.vert; SkinnedMesh.vert). The prelude names the profile's model-view matrix
// OSGACTOR_MODEL_VIEW (not by OpenGL's built-in name here: OSG's State declares its uniform in place of that name
// where it emulates the core profile, which the core prelude declares already) and sets OSGACTOR_INSTANCED:
//   1: instance gl_InstanceID's data starts at texel osgActor_instanceBase + osgActor_instanceTexels * gl_InstanceID
//      of the RGBA32F texture buffer osgActor_instances: its model-view matrix first (4 texels: eye space from the
//      mesh's own frame, OSG's rows as GL's columns), then what the shader reads after it (a skinned mesh's palette);
//   0: the model-view matrix is OpenGL's (OSGACTOR_MODEL_VIEW): the same arithmetic for a mesh drawn one at a time, so
//      that the two paths can be compared bit for bit.
#if OSGACTOR_INSTANCED
uniform samplerBuffer osgActor_instances;
uniform int osgActor_instanceBase;
uniform int osgActor_instanceTexels;
int osgActor_instanceTexel() { return osgActor_instanceBase + osgActor_instanceTexels * gl_InstanceID; }
mat4 osgActor_modelView()
{
    int texel = osgActor_instanceTexel();
    return mat4(texelFetch(osgActor_instances, texel), texelFetch(osgActor_instances, texel + 1),
                texelFetch(osgActor_instances, texel + 2), texelFetch(osgActor_instances, texel + 3));
}
#else
mat4 osgActor_modelView() { return OSGACTOR_MODEL_VIEW; }
#endif
