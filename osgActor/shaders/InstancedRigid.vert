// osgActor's instanced rigid parts (InstancedActorGroup, docs/architecture.md), compiled into the library:
// InstancedActorGroup.cpp puts before it the #version line (1.50 compatibility), OSGACTOR_LIGHTS_ON (the lights to
// light with, LightingCompatibility.glsl) and OSGACTOR_INSTANCED:
//   1: the model-view matrix of instance gl_InstanceID is the four texels from osgActor_instanceBase +
//      4 * gl_InstanceID of osgActor_instances (eye space from the mesh's own frame, OSG's rows as GL's columns);
//   0: it is OpenGL's (gl_ModelViewMatrix): the same arithmetic for a mesh drawn one at a time, so that the two
//      paths can be compared bit for bit.
// The normal goes to eye space by the model-view matrix's linear part, which is its own inverse transpose for the
// rigid frames of joints (rotations and translations; OSG's viewers' view matrices are rigid too), and is normalised,
// as GL_NORMALIZE would; lighting is fixed function's (LightingCompatibility.glsl).
#if OSGACTOR_INSTANCED
uniform samplerBuffer osgActor_instances;
uniform int osgActor_instanceBase;
mat4 osgActor_modelView()
{
    int texel = osgActor_instanceBase + 4 * gl_InstanceID;
    return mat4(texelFetch(osgActor_instances, texel), texelFetch(osgActor_instances, texel + 1),
                texelFetch(osgActor_instances, texel + 2), texelFetch(osgActor_instances, texel + 3));
}
#else
mat4 osgActor_modelView() { return gl_ModelViewMatrix; }
#endif

out vec4 osgActor_colour;

void main()
{
    mat4 modelView = osgActor_modelView();
    vec4 eyePosition = modelView * gl_Vertex;
    gl_Position = gl_ProjectionMatrix * eyePosition;
    vec3 eyeNormal = normalize(mat3(modelView) * gl_Normal);
    osgActor_colour = osgActor_lighting(eyeNormal, eyePosition);
}
