#include <osgActor/core/retarget/RetargetMeasures>
#include <osgActor/core/ActorPose>
#include <osgActor/core/retarget/ClipFrames>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/core/retarget/RetargetLimbs>

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>

namespace osgActor {

namespace {

glm::dvec3 positionOf(const ActorPose& pose, unsigned joint) { return glm::dvec3(pose.getModelMatrix(joint)[3]); }

} // namespace

RetargetMeasures measureRetargetedClip(const RetargetRig& rig, const Clip& source, const RetargetClipResult& result)
{
    RetargetMeasures measures;
    if (!result.clip) return measures;
    const ActorDefinitionPtr& targetDefinition = rig.getTargetDefinition();
    const ActorDefinition& target = *targetDefinition;

    double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
    for (const glm::dmat4& model : rig.getTargetRestModels())
    {
        lowest = std::min(lowest, model[3].z);
        highest = std::max(highest, model[3].z);
    }
    measures.targetHeight = highest - lowest;

    ClipFrames sourceFrames, targetFrames;
    if (!sampleClipFrames(*rig.getSourceDefinition(), source, result.frameRate, sourceFrames).empty() ||
        !sampleClipFrames(target, *result.clip, result.frameRate, targetFrames).empty())
        return measures;
    const unsigned numFrames = std::min(sourceFrames.numFrames, targetFrames.numFrames);

    // The limbs' ends, against the goals the IK pass aims them at.
    const RetargetLimbs limbs = buildRetargetLimbs(rig);
    std::vector<double> errorSums(limbs.limbs.size(), 0.0);
    for (const RetargetLimb& limb : limbs.limbs)
        measures.ends.push_back(RetargetMeasures::End{limb.name, 0.0, 0.0});
    // The contacts' ankles, where they start.
    for (const RetargetFootReport& foot : result.feet)
        for (const FootContact& contact : foot.contacts)
            measures.contacts.push_back(RetargetMeasures::Contact{foot.limb, contact, 0.0});
    std::vector<glm::dvec3> contactStart(measures.contacts.size());
    auto ankleOf = [&](const std::string& limb) {
        return rig.getTargetJointOf(findHAnimJoint(limb == "l_leg" ? "l_ankle" : "r_ankle"));
    };

    // Rest bone lengths.
    std::vector<double> restLength(target.getNumJoints(), 0.0);
    for (unsigned j = 0; j < target.getNumJoints(); ++j)
        if (target.getParent(j) >= 0)
        {
            const unsigned parent = static_cast<unsigned>(target.getParent(j));
            restLength[j] = glm::length(glm::dvec3(rig.getTargetRestModels()[j][3]) -
                                        glm::dvec3(rig.getTargetRestModels()[parent][3]));
        }

    ActorPose sourcePose(rig.getSourceDefinition()), targetPose(targetDefinition);
    for (unsigned f = 0; f < numFrames; ++f)
    {
        sourcePose.setDofs(sourceFrames.frame(f), sourceFrames.numDofs);
        sourcePose.updateMatrices();
        targetPose.setDofs(targetFrames.frame(f), targetFrames.numDofs);
        targetPose.updateMatrices();
        for (unsigned j = 0; j < target.getNumJoints(); ++j)
        {
            const int parent = target.getParent(j);
            // The root's translation carries the travel; every other bone keeps its rest length.
            if (parent < 0 || !(restLength[j] > 0.0) || static_cast<int>(j) == rig.getTargetRoot()) continue;
            const double length =
                glm::length(positionOf(targetPose, j) - positionOf(targetPose, static_cast<unsigned>(parent)));
            measures.largestLengthChange =
                std::max(measures.largestLengthChange, std::abs(length - restLength[j]) / restLength[j]);
        }
        for (std::size_t e = 0; e < limbs.limbs.size(); ++e)
        {
            const RetargetLimb& limb = limbs.limbs[e];
            const glm::dvec3 goal = limb.goal(rig, positionOf(sourcePose, limb.sourceEffector),
                                              positionOf(sourcePose, limb.sourceRoot),
                                              positionOf(targetPose, limb.chain->getRootJoint()));
            const glm::dvec3 end = positionOf(targetPose, limb.chain->getEffectorJoint());
            const double error = glm::length(end - goal);
            RetargetMeasures::End& measured = measures.ends[e];
            measured.largestError = std::max(measured.largestError, error);
            errorSums[e] += error;
            double held = 0.0;
            for (const RetargetFootReport& foot : result.feet)
                if (foot.limb == limb.name)
                    for (std::size_t c = 0; c < foot.contacts.size(); ++c)
                    {
                        held = std::max(held, footHoldWeight(f, foot.contacts[c], result.blendFrames));
                        if (f >= foot.contacts[c].first && f <= foot.contacts[c].last)
                            measured.largestPlantError =
                                std::max(measured.largestPlantError, glm::length(end - foot.plants[c]));
                    }
            if (held == 0.0) measured.largestFollowError = std::max(measured.largestFollowError, error);
        }
        for (std::size_t c = 0; c < measures.contacts.size(); ++c)
        {
            RetargetMeasures::Contact& contact = measures.contacts[c];
            if (f < contact.frames.first || f > contact.frames.last) continue;
            const int ankle = ankleOf(contact.limb);
            if (ankle < 0) continue;
            const glm::dvec3 at = positionOf(targetPose, static_cast<unsigned>(ankle));
            if (f == contact.frames.first) contactStart[c] = at;
            contact.slip = std::max(contact.slip, glm::length(at - contactStart[c]));
            measures.largestSlip = std::max(measures.largestSlip, contact.slip);
        }
    }
    for (std::size_t e = 0; e < measures.ends.size(); ++e)
        measures.ends[e].meanError = numFrames ? errorSums[e] / numFrames : 0.0;
    return measures;
}

} // namespace osgActor
