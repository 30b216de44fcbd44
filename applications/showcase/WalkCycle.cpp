#include "WalkCycle.h"

#include <osg/Math>

#include <algorithm>
#include <cmath>

namespace osgActorShowcase {

namespace {

const double kLegLength = 0.95; // hip to floor, metres (data/humanoid.actor)

void setIfPresent(osgActor::ActorNode& actor, const char* dof, double value)
{
    if (actor.getDofIndex(dof) >= 0) actor.setDof(dof, value);
}

} // namespace

void applyWalkCycle(osgActor::ActorNode& actor, double phase, double hipAmplitude)
{
    const double angle = 2.0 * osg::PI * (phase - std::floor(phase));
    // Hip flexion: negative rx swings a leg forwards (-Y, the way the humanoid faces).
    const double leftHip = -hipAmplitude * std::sin(angle);
    const double rightHip = -leftHip;
    // A leg swings forwards while cos(angle) > 0 (left) or < 0 (right); its knee bends most in mid-swing.
    const double leftSwing = std::max(0.0, std::cos(angle));
    const double rightSwing = std::max(0.0, -std::cos(angle));

    setIfPresent(actor, "l_hip.rx", leftHip);
    setIfPresent(actor, "r_hip.rx", rightHip);
    setIfPresent(actor, "l_knee.rx", 0.08 + 1.0 * leftSwing * leftSwing);
    setIfPresent(actor, "r_knee.rx", 0.08 + 1.0 * rightSwing * rightSwing);
    setIfPresent(actor, "l_ankle.rx", -0.3 * leftSwing);
    setIfPresent(actor, "r_ankle.rx", -0.3 * rightSwing);
    // Arms swing against the legs; elbows stay a little bent.
    setIfPresent(actor, "l_shoulder.rx", 0.8 * -leftHip);
    setIfPresent(actor, "r_shoulder.rx", 0.8 * -rightHip);
    setIfPresent(actor, "l_elbow.rx", -0.35);
    setIfPresent(actor, "r_elbow.rx", -0.35);
    setIfPresent(actor, "vl5.rz", 0.12 * std::sin(angle)); // the chest turns against the hips

    // The stance leg is the one behind the vertical; as it leans, the hip comes down with it.
    const double stanceLean = std::cos(angle) > 0.0 ? rightHip : leftHip;
    setIfPresent(actor, "HumanoidRoot.tz", -kLegLength * (1.0 - std::cos(stanceLean)));
}

} // namespace osgActorShowcase
