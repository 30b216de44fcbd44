// osgActor's instanced rigid parts (InstancedActorGroup, docs/architecture.md), compiled into the library:
// InstancedActorGroup.cpp puts before it the #version line (1.50 compatibility), OSGACTOR_MODEL_VIEW (OpenGL's
// model-view matrix), OSGACTOR_LIGHTS_ON (the lights to light with, LightingCompatibility.glsl) and
// OSGACTOR_INSTANCED, then LightingCompatibility.glsl and
// InstanceData.glsl (osgActor_modelView(): instance gl_InstanceID's, 4 texels each, or OpenGL's).
// The normal goes to eye space by the model-view matrix's linear part, which is its own inverse transpose for the
// rigid frames of joints (rotations and translations; OSG's viewers' view matrices are rigid too), and is normalised,
// as GL_NORMALIZE would; lighting is fixed function's (LightingCompatibility.glsl).
out vec4 osgActor_colour;

void main()
{
    mat4 modelView = osgActor_modelView();
    vec4 eyePosition = modelView * gl_Vertex;
    gl_Position = gl_ProjectionMatrix * eyePosition;
    vec3 eyeNormal = normalize(mat3(modelView) * gl_Normal);
    osgActor_colour = osgActor_lighting(eyeNormal, eyePosition);
}
