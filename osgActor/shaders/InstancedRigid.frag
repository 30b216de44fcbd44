// osgActor's instanced rigid parts: the colour lit per vertex, interpolated, as fixed function's smooth shading.
in vec4 osgActor_colour;

void main() { gl_FragColor = osgActor_colour; }
