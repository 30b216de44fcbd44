/* osgActor: what the OSG state in effect where a skinned mesh draws asks of its skinning program (the lights on, a
 * fragment-only program such as osgShadow's, the units of eye-linear texture generation). Internal to the library. */
#ifndef OSGACTOR_SKINNEDMESHDRAWSTATE_H
#define OSGACTOR_SKINNEDMESHDRAWSTATE_H 1

#include <osgActor/SkinningShaders>

namespace osgUtil { class StateGraph; }

namespace osgActor {

/** Sets key's lights, fragmentProgram and eyeLinearTexGenUnits (compatibility profile) from the state sets of the
  * state graph and those above it, as OpenGL will have them when a drawable of that graph draws, with OSG's
  * OVERRIDE and PROTECTED rules:
  * - lights: the GL_LIGHTi modes on (none when GL_LIGHTING is off; the key's own when no state set sets it);
  * - fragmentProgram: the program in effect, when it has fragment shaders only (isFragmentOnlyProgram()): such a
  *   program leaves the vertex stage to fixed function, which the skinning vertex shader takes the place of;
  * - eyeLinearTexGenUnits: with it, the units with GL_TEXTURE_GEN_S on (taken as eye-linear, as osgShadow's
  *   techniques make them; the TexGen itself is positional state the cull has not reached yet).
  * A key of the core profile is left as it is. */
void applyDrawState(const osgUtil::StateGraph* graph, SkinningProgramKey& key);

} // namespace osgActor

#endif
