// osgActor's skinned-mesh fragment shader (docs/skinning.md), after the profile's prelude (SkinningShaders.cpp):
// the lit colour modulated by the material's base colour texture, as fixed function's GL_MODULATE does.
uniform sampler2D osgActor_baseColorTexture;
uniform bool osgActor_hasBaseColorTexture;

OSGACTOR_VARYING_IN vec4 osgActor_colour;
OSGACTOR_VARYING_IN vec2 osgActor_texCoord;

void main()
{
    vec4 colour = osgActor_colour;
    if (osgActor_hasBaseColorTexture) colour *= OSGACTOR_TEXTURE2D(osgActor_baseColorTexture, osgActor_texCoord);
    OSGACTOR_FRAG_COLOUR = colour;
}
