#include <osgActor/core/retarget/RetargetClip>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/retarget/ClipFrames>
#include <osgActor/core/retarget/RetargetIkJob>
#include <osgActor/core/retarget/RetargetJob>
#include <osgActor/core/retarget/RetargetLimbs>

#include <algorithm>
#include <cmath>

namespace osgActor {

RetargetClipResult retargetClip(const RetargetRig& rig, const Clip& source, const RetargetClipOptions& options)
{
    RetargetClipResult result;
    if (!(options.blendTime >= 0.0) || !std::isfinite(options.blendTime))
    {
        result.error = "retargeting clip '" + source.getName() + "': the blend time must be 0 or more";
        return result;
    }
    const ActorDefinition& target = *rig.getTargetDefinition();
    ClipFrames frames;
    result.error = sampleClipFrames(*rig.getSourceDefinition(), source, options.frameRate, frames);
    if (!result.error.empty()) return result;
    result.numFrames = frames.numFrames;
    result.frameRate = frames.frameRate;

    RetargetWorkspace workspace;
    workspace.resize(rig);
    std::vector<double> targetDofs = rig.getTargetRestDofs();
    RetargetJob job;
    job.rig = &rig;
    job.targetDofs = targetDofs;
    job.workspace = &workspace;
    auto retargetFrame = [&](unsigned f) {
        job.sourceDofs = Span<const double>(frames.frame(f), frames.numDofs);
        job.run(); // validated: the frames are the source's DOF vectors, finite (clips hold finite values)
        result.inexactJoints += job.numInexact;
    };

    // The IK pass's goals: where each limb's end follows the source, and, for planted feet, where it is held.
    RetargetLimbs limbs;
    std::vector<IkGoal> goals;
    std::vector<std::uint8_t> enabled;
    std::vector<std::vector<glm::dvec3>> follow; // per limb, per frame (target model space)
    if (options.ik)
    {
        limbs = buildRetargetLimbs(rig);
        result.notes = limbs.notes;
        const std::size_t numLimbs = limbs.limbs.size();
        follow.assign(numLimbs, std::vector<glm::dvec3>(frames.numFrames));
        std::vector<std::vector<glm::dvec3>> sourceFeet(numLimbs, std::vector<glm::dvec3>(frames.numFrames));
        for (unsigned f = 0; f < frames.numFrames; ++f)
        {
            retargetFrame(f);
            for (std::size_t i = 0; i < numLimbs; ++i)
            {
                const RetargetLimb& limb = limbs.limbs[i];
                sourceFeet[i][f] = workspace.sourcePosition(limb.sourceEffector);
                follow[i][f] = limb.goal(rig, sourceFeet[i][f], workspace.sourcePosition(limb.sourceRoot),
                                         workspace.targetPosition(limb.chain->getRootJoint()));
            }
        }
        for (std::size_t i = 0; i < numLimbs; ++i)
        {
            if (!limbs.limbs[i].isLeg) continue;
            RetargetFootReport foot;
            foot.limb = limbs.limbs[i].name;
            if (options.plantFeet)
                foot.contacts =
                    findFootContacts(sourceFeet[i], frames.frameRate, rig.getSourceHipHeight(), options.contacts);
            for (const FootContact& contact : foot.contacts)
            {
                glm::dvec3 sum(0.0);
                for (unsigned f = contact.first; f <= contact.last; ++f) sum += follow[i][f];
                foot.plants.push_back(sum / double(contact.last - contact.first + 1));
            }
            result.feet.push_back(foot);
        }
        goals.resize(numLimbs);
        enabled.resize(numLimbs);
        result.inexactJoints = 0;
        targetDofs = rig.getTargetRestDofs();
    }

    std::vector<IkWorkspace> ikWorkspaces(limbs.limbs.size());
    for (std::size_t i = 0; i < limbs.limbs.size(); ++i) ikWorkspaces[i].resize(*limbs.limbs[i].chain);
    RetargetIkJob ikJob;
    ikJob.rig = &rig;
    ikJob.limbs = &limbs;
    ikJob.goals = goals;
    ikJob.enabled = enabled;
    ikJob.targetDofs = targetDofs;
    ikJob.workspace = &workspace;
    ikJob.ikWorkspaces = ikWorkspaces;
    const double blendFrames = options.blendTime * frames.frameRate;
    result.blendFrames = blendFrames;

    std::vector<double> values(std::size_t(frames.numFrames) * target.getNumDofs());
    for (unsigned f = 0; f < frames.numFrames; ++f)
    {
        retargetFrame(f);
        if (options.ik && !limbs.limbs.empty())
        {
            std::size_t foot = 0;
            for (std::size_t i = 0; i < limbs.limbs.size(); ++i)
            {
                goals[i].position = follow[i][f];
                enabled[i] = limbs.limbs[i].isLeg ? options.followFeet : options.followHands;
                if (!limbs.limbs[i].isLeg) continue;
                const RetargetFootReport& report = result.feet[foot++];
                // Held at the plant during a contact; before and after, following the source with the plant's
                // correction at the contact's edge faded in and out, so a swinging foot is not pulled off its path.
                double weight = 0.0;
                std::size_t held = 0;
                for (std::size_t c = 0; c < report.contacts.size(); ++c)
                {
                    const double w = footHoldWeight(f, report.contacts[c], blendFrames);
                    if (w > weight)
                    {
                        weight = w;
                        held = c;
                    }
                }
                if (weight > 0.0)
                {
                    const FootContact& contact = report.contacts[held];
                    const unsigned edge = f < contact.first ? contact.first : contact.last;
                    goals[i].position = weight == 1.0 ? report.plants[held]
                                                      : follow[i][f] + weight * (report.plants[held] - follow[i][edge]);
                    enabled[i] = 1;
                }
            }
            ikJob.run();
            result.largestIkError = std::max(result.largestIkError, ikJob.largestError);
            result.largestRootDrop = std::max(result.largestRootDrop, ikJob.rootDrop);
        }
        std::copy(targetDofs.begin(), targetDofs.end(), values.begin() + std::ptrdiff_t(f) * target.getNumDofs());
    }

    ClipBuilder builder(options.name.empty() ? source.getName() : options.name);
    for (unsigned d = 0; d < target.getNumDofs(); ++d) builder.addChannel(target.getDofName(d));
    builder.setFrames(frames.frameRate, std::move(values));
    const ClipBuildResult built = builder.build();
    if (!built)
    {
        result.error = "retargeting clip '" + source.getName() + "': " + built.error;
        return result;
    }
    result.clip = built.clip;
    return result;
}

} // namespace osgActor
