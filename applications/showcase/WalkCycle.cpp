#include "WalkCycle.h"

#include <osg/Math>

#include <algorithm>
#include <cmath>

namespace osgActorShowcase {

namespace {

const double kLegLength = 0.95; // hip to floor, metres (data/humanoid.actor)

} // namespace

std::vector<WalkCycleValue> walkCyclePose(double phase, double hipAmplitude)
{
    const double angle = 2.0 * osg::PI * (phase - std::floor(phase));
    // Hip flexion: negative rx swings a leg forwards (-Y, the way the humanoid faces).
    const double leftHip = -hipAmplitude * std::sin(angle);
    const double rightHip = -leftHip;
    // A leg swings forwards while cos(angle) > 0 (left) or < 0 (right); its knee bends most in mid-swing.
    const double leftSwing = std::max(0.0, std::cos(angle));
    const double rightSwing = std::max(0.0, -std::cos(angle));
    // The stance leg is the one behind the vertical; as it leans, the hip comes down with it.
    const double stanceLean = std::cos(angle) > 0.0 ? rightHip : leftHip;
    return {
        {"l_hip.rx", leftHip},
        {"r_hip.rx", rightHip},
        {"l_knee.rx", 0.08 + 1.0 * leftSwing * leftSwing},
        {"r_knee.rx", 0.08 + 1.0 * rightSwing * rightSwing},
        {"l_ankle.rx", -0.3 * leftSwing},
        {"r_ankle.rx", -0.3 * rightSwing},
        // Arms swing against the legs; elbows stay a little bent.
        {"l_shoulder.rx", 0.8 * -leftHip},
        {"r_shoulder.rx", 0.8 * -rightHip},
        {"l_elbow.rx", -0.35},
        {"r_elbow.rx", -0.35},
        {"vl5.rz", 0.12 * std::sin(angle)}, // the chest turns against the hips
        {"HumanoidRoot.tz", -kLegLength * (1.0 - std::cos(stanceLean))},
    };
}

osgActor::ClipBuildResult makeWalkCycleClip(const osgActor::ActorDefinition& definition, double cycleDuration,
                                            unsigned framesPerCycle)
{
    osgActor::ClipBuildResult result;
    if (!(cycleDuration > 0.0) || !std::isfinite(cycleDuration) || framesPerCycle < 2)
    {
        result.error = "walk cycle: the cycle needs a positive duration and at least 2 frames";
        return result;
    }
    // The channels: the walk's DOFs this definition has, in the walk's order.
    std::vector<bool> present;
    osgActor::ClipBuilder builder("walk cycle");
    for (const WalkCycleValue& value : walkCyclePose(0.0))
    {
        present.push_back(definition.findDof(value.dof) >= 0);
        if (present.back()) builder.addChannel(value.dof);
    }
    if (builder.getNumChannels() == 0)
    {
        result.error =
            "walk cycle: actor '" + definition.getName() + "' has none of the DOFs of a walk (l_hip.rx, ...)";
        return result;
    }
    std::vector<double> frames;
    for (unsigned f = 0; f <= framesPerCycle; ++f)
    {
        const std::vector<WalkCycleValue> pose = walkCyclePose(double(f) / framesPerCycle);
        for (std::size_t c = 0; c < pose.size(); ++c)
            if (present[c]) frames.push_back(pose[c].value);
    }
    builder.setFrames(framesPerCycle / cycleDuration, std::move(frames));
    return builder.build();
}

} // namespace osgActorShowcase
