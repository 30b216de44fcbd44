/* osgActorShowcase: a procedural walk for a humanoid with H-Anim joint names (data/humanoid.actor), as a clip. */
#ifndef OSGACTORSHOWCASE_WALKCYCLE_H
#define OSGACTORSHOWCASE_WALKCYCLE_H 1

#include "Export.h"

#include <osgActor/core/ActorDefinition>
#include <osgActor/core/ClipBuilder>

#include <vector>

namespace osgActorShowcase {

/** One DOF of the walk and its value (radians, or model units for translations). */
struct WalkCycleValue
{
    const char* dof; // "l_hip.rx", ...
    double value;
};

/** A humanoid's pose at a point of its walk cycle: phase 0..1 is one full cycle (two steps), 0 is the left leg in
  * mid-swing. Hips swing by hipAmplitude (radians) either side, the swinging knee bends, the arms swing against the
  * legs, and the pelvis (HumanoidRoot.tz) drops as the stance leg leans so that the feet stay on the floor. */
OSGACTORSHOWCASE_EXPORT std::vector<WalkCycleValue> walkCyclePose(double phase, double hipAmplitude = 0.35);

/** The walk cycle as a clip of frames for one definition, to loop with a ClipPlayer: one cycle in cycleDuration
  * seconds (> 0), framesPerCycle frames (>= 2) plus a last one equal to the first, channels for the DOFs of
  * walkCyclePose() that the definition has. Refuses (and says why) a definition with none of them. */
OSGACTORSHOWCASE_EXPORT osgActor::ClipBuildResult makeWalkCycleClip(const osgActor::ActorDefinition& definition,
                                                                    double cycleDuration,
                                                                    unsigned framesPerCycle = 40);

} // namespace osgActorShowcase

#endif
