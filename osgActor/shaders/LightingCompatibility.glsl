// Fixed-function lighting of one vertex, from the compatibility profile's built-in state: the lights that
// OSGACTOR_LIGHTS_ON marks (eight booleans, one per GL_LIGHTi: those the state in effect where the mesh draws turns
// on, as OpenGL lights a rigid mesh there) and the front material (OpenGL 2.1, section 2.14.1), with no local viewer and
// one-sided lighting, as OSG's default state has it; a light with w = 0 is directional, otherwise positional with its
// attenuation and spot cone. The result is clamped to [0, 1] and its alpha is the material's diffuse alpha, as fixed
// function's are.
vec4 osgActor_light(int i, vec3 eyeNormal, vec4 eyePosition)
{
    vec3 toLight;
    float attenuation = 1.0;
    if (gl_LightSource[i].position.w == 0.0)
    {
        toLight = normalize(gl_LightSource[i].position.xyz);
    }
    else
    {
        vec3 offset = gl_LightSource[i].position.xyz / gl_LightSource[i].position.w - eyePosition.xyz / eyePosition.w;
        float distance = length(offset);
        toLight = offset / distance;
        attenuation = 1.0 / (gl_LightSource[i].constantAttenuation + gl_LightSource[i].linearAttenuation * distance +
                             gl_LightSource[i].quadraticAttenuation * distance * distance);
        if (gl_LightSource[i].spotCutoff <= 90.0)
        {
            float spot = dot(-toLight, normalize(gl_LightSource[i].spotDirection));
            attenuation *= spot < gl_LightSource[i].spotCosCutoff ? 0.0 : pow(spot, gl_LightSource[i].spotExponent);
        }
    }
    float diffuse = max(dot(eyeNormal, toLight), 0.0);
    vec4 colour = attenuation * (gl_FrontLightProduct[i].ambient + diffuse * gl_FrontLightProduct[i].diffuse);
    if (diffuse > 0.0)
    {
        float highlight = max(dot(eyeNormal, normalize(toLight + vec3(0.0, 0.0, 1.0))), 0.0);
        // pow(x, 0) is undefined at x = 0 in GLSL; fixed function takes it as 1.
        float shine = gl_FrontMaterial.shininess > 0.0 ? pow(highlight, gl_FrontMaterial.shininess) : 1.0;
        colour += attenuation * shine * gl_FrontLightProduct[i].specular;
    }
    return colour;
}

vec4 osgActor_lighting(vec3 eyeNormal, vec4 eyePosition)
{
    const bool lit[8] = OSGACTOR_LIGHTS_ON;
    vec4 colour = gl_FrontLightModelProduct.sceneColor;
    for (int i = 0; i < 8; ++i)
        if (lit[i]) colour += osgActor_light(i, eyeNormal, eyePosition);
    colour = clamp(colour, 0.0, 1.0);
    colour.a = gl_FrontMaterial.diffuse.a;
    return colour;
}
