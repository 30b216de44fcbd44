/* osgActorShowcase: a procedural walk for a humanoid with H-Anim joint names (data/humanoid.actor). */
#ifndef OSGACTORSHOWCASE_WALKCYCLE_H
#define OSGACTORSHOWCASE_WALKCYCLE_H 1

#include "Export.h"

#include <osgActor/ActorNode>

namespace osgActorShowcase {

/** Poses a humanoid at a point of its walk cycle: phase 0..1 is one full cycle (two steps), 0 is the left leg in
  * mid-swing. Hips swing by hipAmplitude (radians) either side, the swinging knee bends, the arms swing against the
  * legs, and the pelvis (HumanoidRoot.tz) drops as the stance leg leans so that the feet stay on the floor. Joints
  * the actor does not have are skipped. */
OSGACTORSHOWCASE_EXPORT void applyWalkCycle(osgActor::ActorNode& actor, double phase, double hipAmplitude = 0.35);

} // namespace osgActorShowcase

#endif
