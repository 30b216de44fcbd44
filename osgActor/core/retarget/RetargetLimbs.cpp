#include <osgActor/core/retarget/RetargetLimbs>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/core/retarget/JointRotationFit>

#include <glm/geometric.hpp>

#include <cmath>

namespace osgActor {

namespace {

/** The target's joint of an H-Anim joint name, or -1. */
int targetJoint(const RetargetRig& rig, const char* hanim) { return rig.getTargetJointOf(findHAnimJoint(hanim)); }

glm::dvec3 restPosition(const RetargetRig& rig, int joint)
{
    return glm::dvec3(rig.getTargetRestModels()[static_cast<unsigned>(joint)][3]);
}

/** The body's forward direction at rest on the target (horizontal, from its left and right hips or shoulders). */
glm::dvec3 targetForward(const RetargetRig& rig)
{
    static const char* const kPairs[][2] = {{"l_hip", "r_hip"}, {"l_shoulder", "r_shoulder"}};
    for (const auto& pair : kPairs)
    {
        const int left = targetJoint(rig, pair[0]), right = targetJoint(rig, pair[1]);
        if (left < 0 || right < 0) continue;
        glm::dvec3 lateral = restPosition(rig, left) - restPosition(rig, right);
        lateral.z = 0.0;
        if (glm::length(lateral) > 1e-12) return glm::normalize(glm::cross(lateral, glm::dvec3(0.0, 0.0, 1.0)));
    }
    return glm::dvec3(0.0, -1.0, 0.0);
}

/** The rotation slot of the middle joint whose axis at rest lies nearest the hinge axis (model space). */
unsigned hingeSlot(const RetargetRig& rig, unsigned middle, const glm::dvec3& hinge)
{
    const ActorDefinition& target = *rig.getTargetDefinition();
    const JointKinematics& k = target.getKinematics(middle);
    const int parent = target.getParent(middle);
    glm::dmat3 frame = (parent >= 0 ? glm::dmat3(rig.getTargetRestModels()[static_cast<unsigned>(parent)])
                                    : glm::dmat3(1.0)) *
                       rig.getTargetOffsetRotations()[middle];
    const double* rest = rig.getTargetRestDofs().data();
    unsigned best = 0;
    double bestAlignment = -1.0;
    for (unsigned r = 0; r < k.numRotations; ++r)
    {
        const double alignment = std::abs(glm::dot(frame[k.rotationAxis[r]], hinge));
        if (alignment > bestAlignment)
        {
            bestAlignment = alignment;
            best = r;
        }
        const double angle = rest[k.rotationDof[r]];
        postRotateAxis(frame, k.rotationAxis[r], std::cos(angle), std::sin(angle));
    }
    return best;
}

} // namespace

RetargetLimbs buildRetargetLimbs(const RetargetRig& rig)
{
    RetargetLimbs result;
    const ActorDefinition& target = *rig.getTargetDefinition();
    const glm::dvec3 forward = targetForward(rig);
    static const char* const kLimbs[][4] = {{"l_leg", "l_hip", "l_knee", "l_ankle"},
                                            {"r_leg", "r_hip", "r_knee", "r_ankle"},
                                            {"l_arm", "l_shoulder", "l_elbow", "l_wrist"},
                                            {"r_arm", "r_shoulder", "r_elbow", "r_wrist"}};
    for (const auto& limb : kLimbs)
    {
        const int root = targetJoint(rig, limb[1]), middle = targetJoint(rig, limb[2]), end = targetJoint(rig, limb[3]);
        const int sourceRoot = rig.getSourceJointOf(findHAnimJoint(limb[1]));
        const int sourceMiddle = rig.getSourceJointOf(findHAnimJoint(limb[2]));
        const int sourceEnd = rig.getSourceJointOf(findHAnimJoint(limb[3]));
        if (root < 0 || middle < 0 || end < 0 || sourceRoot < 0 || sourceMiddle < 0 || sourceEnd < 0)
        {
            result.notes.push_back(std::string(limb[0]) + ": its three joints are not on both skeletons, no IK");
            continue;
        }
        IkChainSpec spec;
        spec.name = limb[0];
        spec.rootJoint = target.getJointName(static_cast<unsigned>(root));
        spec.effectorJoint = target.getJointName(static_cast<unsigned>(end));
        // The end joint is held: the pass gives it its retargeted orientation after the solve.
        auto freeze = [&spec, &target](unsigned joint, bool keepOneRotation, unsigned keptSlot) {
            const JointKinematics& k = target.getKinematics(joint);
            for (unsigned r = 0; r < k.numRotations; ++r)
                if (!keepOneRotation || r != keptSlot)
                    spec.dofWeights.push_back({target.getDofName(k.rotationDof[r]), 0.0});
            for (int dof : k.translationDof)
                if (dof >= 0) spec.dofWeights.push_back({target.getDofName(static_cast<unsigned>(dof)), 0.0});
        };
        freeze(static_cast<unsigned>(end), false, 0);
        const bool limbOfThree = target.getParent(static_cast<unsigned>(end)) == middle &&
                                 target.getParent(static_cast<unsigned>(middle)) == root;
        if (limbOfThree)
        {
            const glm::dvec3 along = restPosition(rig, middle) - restPosition(rig, root);
            glm::dvec3 hinge = glm::cross(along, forward);
            if (!(glm::length(hinge) > 1e-9 * glm::length(along))) hinge = glm::cross(forward, glm::dvec3(0, 0, 1));
            freeze(static_cast<unsigned>(middle), true, hingeSlot(rig, static_cast<unsigned>(middle),
                                                                   glm::normalize(hinge)));
            for (int dof : target.getKinematics(static_cast<unsigned>(root)).translationDof)
                if (dof >= 0) spec.dofWeights.push_back({target.getDofName(static_cast<unsigned>(dof)), 0.0});
            spec.solver = IkSolverType::TwoBone;
        }
        else
            spec.solver = IkSolverType::Dls;
        IkChainBuildResult built = buildIkChain(target, spec);
        if (!built && spec.solver == IkSolverType::TwoBone)
        {
            spec.solver = IkSolverType::Dls;
            built = buildIkChain(target, spec);
        }
        if (!built)
        {
            result.notes.push_back(std::string(limb[0]) + ": " + built.error);
            continue;
        }
        RetargetLimb made;
        made.name = limb[0];
        made.isLeg = std::string(limb[0]).find("leg") != std::string::npos;
        made.chain = built.chain;
        made.sourceEffector = static_cast<unsigned>(sourceEnd);
        made.sourceRoot = static_cast<unsigned>(sourceRoot);
        auto sourceAt = [&rig](int joint) {
            return glm::dvec3(rig.getSourceRestModels()[static_cast<unsigned>(joint)][3]);
        };
        const double sourceLength = glm::length(sourceAt(sourceMiddle) - sourceAt(sourceRoot)) +
                                    glm::length(sourceAt(sourceEnd) - sourceAt(sourceMiddle));
        const double targetLength = glm::length(restPosition(rig, middle) - restPosition(rig, root)) +
                                    glm::length(restPosition(rig, end) - restPosition(rig, middle));
        made.lengthRatio = sourceLength > 0.0 ? targetLength / sourceLength : rig.getScale();
        result.limbs.push_back(made);
    }
    return result;
}

} // namespace osgActor
