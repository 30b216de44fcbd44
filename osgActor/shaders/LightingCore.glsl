// Lighting of one vertex in the core profile, which has no built-in light or material: fixed function's formula for
// one directional light (OpenGL 2.1, section 2.14.1; no local viewer, no specular term, as createMaterialStateSet's
// materials have none), from uniforms whose defaults are the headlight OSG's viewers set up (osgViewer::View and
// osgUtil::SceneView: light 0 along the eye's +Z, diffuse 0.8, ambient 0, and a scene ambient of 0.1) and the
// material's base colour (createMaterialStateSet sets osgActor_baseColor; diffuse and ambient are both that colour).
uniform vec3 osgActor_lightDirection = vec3(0.0, 0.0, 1.0);
uniform vec4 osgActor_lightDiffuse = vec4(0.8, 0.8, 0.8, 1.0);
uniform vec4 osgActor_lightAmbient = vec4(0.0, 0.0, 0.0, 1.0);
uniform vec4 osgActor_sceneAmbient = vec4(0.1, 0.1, 0.1, 1.0);
uniform vec4 osgActor_baseColor = vec4(1.0);

vec4 osgActor_lighting(vec3 eyeNormal, vec4 eyePosition)
{
    float diffuse = max(dot(eyeNormal, normalize(osgActor_lightDirection)), 0.0);
    vec4 colour = osgActor_baseColor * (osgActor_sceneAmbient + osgActor_lightAmbient + diffuse * osgActor_lightDiffuse);
    colour = clamp(colour, 0.0, 1.0);
    colour.a = osgActor_baseColor.a;
    return colour;
}
