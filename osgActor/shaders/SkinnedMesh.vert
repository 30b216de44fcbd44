// osgActor's skinned-mesh vertex shader (docs/skinning.md), compiled into the library: SkinningShaders.cpp puts a
// prelude before it that sets the GLSL version, the profile's names for OSG's vertex inputs and matrices, and the
// variant's defines:
//   OSGACTOR_SKINNING            1: bind-space vertices moved by the palette; 0: vertices already in model space
//                                (the CPU path in the core profile, or a rigid mesh)
//   OSGACTOR_INFLUENCES          4 or 8 joints per vertex
//   OSGACTOR_DUAL_QUATERNION     1: dual-quaternion skinning; 0: linear blend
//   OSGACTOR_INVERSE_TRANSPOSE   1: linear-blend normals by the blend of inverse-transposed linear parts
//   OSGACTOR_PALETTE_BUFFER      1: the palette in a texture buffer; 0: in a uniform array of
//                                OSGACTOR_PALETTE_VECTORS vec4s
//   OSGACTOR_PALETTE_STRIDE      vec4 rows per joint in the palette
//   OSGACTOR_LIGHTS_ON           compatibility profile: bool[8](...), whether to light with GL_LIGHT0 .. GL_LIGHT7
//   OSGACTOR_FIXED_FUNCTION_OUTPUTS  compatibility profile, 1: also write what fixed function's vertex stage writes
//                                for a fragment shader of someone else's (osgShadow's, for one) linked with this one:
//                                gl_FrontColor, gl_TexCoord[0] and the eye-linear texture coordinates of the units in
//                                OSGACTOR_EYE_LINEAR_UNITS (a bit per unit), each through its texture matrix
//   OSGACTOR_INSTANCED_ARITHMETIC  1: the instanced draws' arithmetic (InstancedActorGroup):
//                                the eye position by osgActor_modelView() (InstanceData.glsl, which the prelude then
//                                puts before this file), then the projection; the normal by the model-view matrix's
//                                linear part (rigid or uniformly scaled frames: an actor's and the view's), normalised
//   OSGACTOR_INSTANCED           with it, 1: the model-view matrix and the palette of instance gl_InstanceID from the
//                                instances' texture buffer (its palette in the texels after its matrix); 0: OpenGL's
//                                model-view matrix and the palette storage's palette (the same pixels, drawn one
//                                mesh at a time)
//
// The palette holds, per skin joint j, OSGACTOR_PALETTE_STRIDE rows from row j * stride:
//   linear blend:  rows 0..2 the first three rows of the skinning matrix (model x inverse bind: bind space to model
//                  space, model units), rows 3..5 (inverse transpose only) those of its linear part's inverse
//                  transpose;
//   dual quaternion: row 0 the unit dual quaternion's real part (x, y, z, w), row 1 its dual part.
//
// Lighting is what OpenGL's fixed function computes per vertex for the material and the lights on where the mesh
// draws, so that a skinned mesh looks like a rigid one of the same material: osgActor_lighting() reads the
// compatibility profile's built-in light and material state, or, in the core profile, uniforms with the headlight's
// values (light 0 of OSG's viewers).

#if OSGACTOR_SKINNING
#if OSGACTOR_INSTANCED
// The instance's palette follows its model-view matrix in its data (InstanceData.glsl).
vec4 osgActor_paletteRow(int row) { return texelFetch(osgActor_instances, osgActor_instanceTexel() + 4 + row); }
#elif OSGACTOR_PALETTE_BUFFER
uniform samplerBuffer osgActor_palette;
vec4 osgActor_paletteRow(int row) { return texelFetch(osgActor_palette, row); }
#else
uniform vec4 osgActor_palette[OSGACTOR_PALETTE_VECTORS];
vec4 osgActor_paletteRow(int row) { return osgActor_palette[row]; }
#endif

// Joint indices are exact in floats. With 8 influences each component holds two joints, first + 4096 * second.
OSGACTOR_ATTRIBUTE vec4 osgActor_joints;
OSGACTOR_ATTRIBUTE vec4 osgActor_weights;
#if OSGACTOR_INFLUENCES == 8
OSGACTOR_ATTRIBUTE vec4 osgActor_weights1;
#endif

#if OSGACTOR_DUAL_QUATERNION
uniform float osgActor_bindScale;
#endif

/** The skinned vertex: model-space position and normal (not normalised). */
struct osgActor_SkinnedVertex
{
    vec3 position;
    vec3 normal;
};

#if OSGACTOR_DUAL_QUATERNION
void osgActor_accumulate(int joint, float weight, vec4 firstReal, inout vec4 real, inout vec4 dual)
{
    int row = joint * OSGACTOR_PALETTE_STRIDE;
    vec4 jointReal = osgActor_paletteRow(row);
    // q and -q are the same rotation: blend each joint's on the first joint's hemisphere.
    float signedWeight = dot(jointReal, firstReal) < 0.0 ? -weight : weight;
    real += signedWeight * jointReal;
    dual += signedWeight * osgActor_paletteRow(row + 1);
}
#else
void osgActor_accumulate(int joint, float weight, inout vec4 row0, inout vec4 row1, inout vec4 row2,
                         inout vec4 normal0, inout vec4 normal1, inout vec4 normal2)
{
    int row = joint * OSGACTOR_PALETTE_STRIDE;
    row0 += weight * osgActor_paletteRow(row);
    row1 += weight * osgActor_paletteRow(row + 1);
    row2 += weight * osgActor_paletteRow(row + 2);
#if OSGACTOR_INVERSE_TRANSPOSE
    normal0 += weight * osgActor_paletteRow(row + 3);
    normal1 += weight * osgActor_paletteRow(row + 4);
    normal2 += weight * osgActor_paletteRow(row + 5);
#endif
}
#endif

osgActor_SkinnedVertex osgActor_skin(vec3 bindPosition, vec3 bindNormal)
{
#if OSGACTOR_INFLUENCES == 8
    vec4 high = floor(osgActor_joints / 4096.0);
    vec4 low = osgActor_joints - 4096.0 * high;
    float joints[8];
    float weights[8];
    for (int k = 0; k < 4; ++k)
    {
        joints[k] = low[k];
        joints[k + 4] = high[k];
        weights[k] = osgActor_weights[k];
        weights[k + 4] = osgActor_weights1[k];
    }
#else
    float joints[4];
    float weights[4];
    for (int k = 0; k < 4; ++k)
    {
        joints[k] = osgActor_joints[k];
        weights[k] = osgActor_weights[k];
    }
#endif
    osgActor_SkinnedVertex result;
#if OSGACTOR_DUAL_QUATERNION
    vec4 firstReal = osgActor_paletteRow(int(joints[0]) * OSGACTOR_PALETTE_STRIDE);
    vec4 real = vec4(0.0);
    vec4 dual = vec4(0.0);
    for (int k = 0; k < OSGACTOR_INFLUENCES; ++k)
        if (weights[k] > 0.0) osgActor_accumulate(int(joints[k]), weights[k], firstReal, real, dual);
    // The normalised blend moves the scaled bind position rigidly: rotation by real / |real|, then the translation
    // 2 dual real* / |real|^2 (its vector part).
    float inverseLength2 = 1.0 / dot(real, real);
    vec3 scaled = osgActor_bindScale * bindPosition;
    vec3 turned = scaled + 2.0 * inverseLength2 * cross(real.xyz, cross(real.xyz, scaled) + real.w * scaled);
    vec3 translation = 2.0 * inverseLength2 * (real.w * dual.xyz - dual.w * real.xyz + cross(real.xyz, dual.xyz));
    result.position = turned + translation;
    result.normal = bindNormal + 2.0 * inverseLength2 * cross(real.xyz, cross(real.xyz, bindNormal) + real.w * bindNormal);
#else
    vec4 row0 = vec4(0.0);
    vec4 row1 = vec4(0.0);
    vec4 row2 = vec4(0.0);
    vec4 normal0 = vec4(0.0);
    vec4 normal1 = vec4(0.0);
    vec4 normal2 = vec4(0.0);
    for (int k = 0; k < OSGACTOR_INFLUENCES; ++k)
        if (weights[k] > 0.0)
            osgActor_accumulate(int(joints[k]), weights[k], row0, row1, row2, normal0, normal1, normal2);
    vec4 position = vec4(bindPosition, 1.0);
    result.position = vec3(dot(row0, position), dot(row1, position), dot(row2, position));
#if OSGACTOR_INVERSE_TRANSPOSE
    result.normal = vec3(dot(normal0.xyz, bindNormal), dot(normal1.xyz, bindNormal), dot(normal2.xyz, bindNormal));
#else
    result.normal = vec3(dot(row0.xyz, bindNormal), dot(row1.xyz, bindNormal), dot(row2.xyz, bindNormal));
#endif
#endif
    return result;
}
#endif

#if OSGACTOR_FIXED_FUNCTION_OUTPUTS
/** Texture unit i's coordinates as fixed function's eye-linear texture generation makes them (OpenGL 2.1, section
  * 2.11.4: the eye planes as the TexGen set them, already in eye space), then its texture matrix. */
vec4 osgActor_eyeLinear(int i, vec4 eyePosition)
{
    vec4 generated = vec4(dot(gl_EyePlaneS[i], eyePosition), dot(gl_EyePlaneT[i], eyePosition),
                          dot(gl_EyePlaneR[i], eyePosition), dot(gl_EyePlaneQ[i], eyePosition));
    return gl_TextureMatrix[i] * generated;
}
#endif

/** The model-space position of the vertex (model units), for transform feedback (tests capture it). */
OSGACTOR_VARYING_OUT vec3 osgActor_modelPosition;
OSGACTOR_VARYING_OUT vec4 osgActor_colour;
OSGACTOR_VARYING_OUT vec2 osgActor_texCoord;

void main()
{
#if OSGACTOR_SKINNING
    osgActor_SkinnedVertex skinned = osgActor_skin(OSGACTOR_VERTEX.xyz, OSGACTOR_NORMAL);
    vec3 position = skinned.position;
    vec3 normal = skinned.normal;
#else
    vec3 position = OSGACTOR_VERTEX.xyz;
    vec3 normal = OSGACTOR_NORMAL;
#endif
    osgActor_modelPosition = position;
    vec4 modelPosition = vec4(position, 1.0);
#if OSGACTOR_INSTANCED_ARITHMETIC
    mat4 modelView = osgActor_modelView();
    vec4 eyePosition = modelView * modelPosition;
    gl_Position = OSGACTOR_PROJECTION * eyePosition;
    vec3 eyeNormal = normalize(mat3(modelView) * normal);
#else
    gl_Position = OSGACTOR_MODEL_VIEW_PROJECTION * modelPosition;
    vec4 eyePosition = OSGACTOR_MODEL_VIEW * modelPosition;
    vec3 eyeNormal = normalize(OSGACTOR_NORMAL_MATRIX * normal);
#endif
    osgActor_colour = osgActor_lighting(eyeNormal, eyePosition);
    osgActor_texCoord = OSGACTOR_TEXCOORD0.xy;
#if OSGACTOR_FIXED_FUNCTION_OUTPUTS
    gl_FrontColor = osgActor_colour;
    gl_TexCoord[0] = gl_TextureMatrix[0] * OSGACTOR_TEXCOORD0;
#if OSGACTOR_EYE_LINEAR_UNITS & 2
    gl_TexCoord[1] = osgActor_eyeLinear(1, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 4
    gl_TexCoord[2] = osgActor_eyeLinear(2, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 8
    gl_TexCoord[3] = osgActor_eyeLinear(3, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 16
    gl_TexCoord[4] = osgActor_eyeLinear(4, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 32
    gl_TexCoord[5] = osgActor_eyeLinear(5, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 64
    gl_TexCoord[6] = osgActor_eyeLinear(6, eyePosition);
#endif
#if OSGACTOR_EYE_LINEAR_UNITS & 128
    gl_TexCoord[7] = osgActor_eyeLinear(7, eyePosition);
#endif
#endif
}
