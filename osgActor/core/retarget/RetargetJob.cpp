#include <osgActor/core/retarget/RetargetJob>
#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/detail/SinCos>
#include <osgActor/core/ik/IkKinematics>

#include "../detail/HotPath.h"

#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace osgActor {

void RetargetWorkspace::resize(const RetargetRig& rig)
{
    const ActorDefinition& source = *rig.getSourceDefinition();
    const ActorDefinition& target = *rig.getTargetDefinition();
    sines.assign(source.getNumDofs(), 0.0);
    cosines.assign(source.getNumDofs(), 1.0);
    sourceRotations.assign(source.getNumJoints(), glm::dmat3(1.0));
    sourcePositions.assign(source.getNumJoints(), glm::dvec3(0.0));
    targetRotations.assign(target.getNumJoints(), glm::dmat3(1.0));
    targetPositions.assign(target.getNumJoints(), glm::dvec3(0.0));
    targetExact.assign(target.getNumJoints(), 0);
}

bool RetargetWorkspace::fits(const RetargetRig& rig) const
{
    const ActorDefinition& source = *rig.getSourceDefinition();
    const ActorDefinition& target = *rig.getTargetDefinition();
    return sines.size() == source.getNumDofs() && cosines.size() == source.getNumDofs() &&
           sourceRotations.size() == source.getNumJoints() && sourcePositions.size() == source.getNumJoints() &&
           targetRotations.size() == target.getNumJoints() && targetPositions.size() == target.getNumJoints() &&
           targetExact.size() == target.getNumJoints();
}

bool RetargetJob::validate() const
{
    if (!rig || !workspace || !workspace->fits(*rig)) return false;
    if (sourceDofs.size() != rig->getSourceDefinition()->getNumDofs()) return false;
    if (targetDofs.size() != rig->getTargetDefinition()->getNumDofs()) return false;
    for (double value : sourceDofs)
        if (!(std::abs(value) <= kMaxDofMagnitude)) return false; // also refuses NaN
    for (double value : targetDofs)
        if (!std::isfinite(value)) return false;
    return true;
}

namespace {

/** The point a joint's origin is at in its parent's frame (local space): its offset, moved by its translation DOFs
  * before or after its rotation (localRotation: offset rotation times the DOFs' rotation). */
glm::dvec3 jointOrigin(const JointKinematics& k, const glm::dmat3& offsetRotation, const glm::dmat3& localRotation,
                       const double* dofs)
{
    const glm::dvec3 offset(k.offset[3]);
    if (!k.hasTranslation) return offset;
    const glm::dvec3 slide = jointSlide(k, dofs);
    return offset + (k.translationMode == TranslationMode::BeforeRotation ? offsetRotation : localRotation) * slide;
}

/** The model-space rotation change of a source joint since the rest pose, as a quaternion; identity for -1. */
glm::dquat changeSinceRest(const RetargetRig& rig, const RetargetWorkspace& w, int joint)
{
    if (joint < 0) return glm::dquat(1.0, 0.0, 0.0, 0.0);
    const unsigned j = static_cast<unsigned>(joint);
    return glm::quat_cast(w.sourceRotations[j] * glm::transpose(glm::dmat3(rig.getSourceRestModels()[j])));
}

} // namespace

OSGACTOR_HOT_PATH bool RetargetJob::run()
{
    if (!validate()) return false;
    const ActorDefinition& source = *rig->getSourceDefinition();
    const ActorDefinition& target = *rig->getTargetDefinition();
    RetargetWorkspace& w = *workspace;
    const double* sourceValues = sourceDofs.data();
    double* targetValues = targetDofs.data();

    // The source's forward kinematics, rotations and positions (model space).
    sinCos(sourceValues, w.sines.data(), w.cosines.data(), source.getNumDofs());
    const std::vector<glm::dmat3>& sourceOffsets = rig->getSourceOffsetRotations();
    for (unsigned j = 0; j < source.getNumJoints(); ++j)
    {
        const JointKinematics& k = source.getKinematics(j);
        const glm::dmat3 local = jointRotation(sourceOffsets[j], k, w.cosines.data(), w.sines.data());
        const glm::dvec3 origin = jointOrigin(k, sourceOffsets[j], local, sourceValues);
        const int parent = source.getParent(j);
        if (parent < 0)
        {
            w.sourceRotations[j] = local;
            w.sourcePositions[j] = origin;
        }
        else
        {
            const glm::dmat3& parentRotation = w.sourceRotations[static_cast<unsigned>(parent)];
            w.sourceRotations[j] = multiply(parentRotation, local);
            w.sourcePositions[j] = w.sourcePositions[static_cast<unsigned>(parent)] + parentRotation * origin;
        }
    }

    // The target, parents first.
    const std::vector<RetargetJointPlan>& plans = rig->getPlans();
    const std::vector<glm::dmat3>& targetOffsets = rig->getTargetOffsetRotations();
    const std::vector<glm::dmat3>& restLocals = rig->getTargetRestLocalRotations();
    const std::vector<double>& rest = rig->getTargetRestDofs();
    const bool aligned = rig->isAlignmentIdentity();
    const glm::dmat3& alignment = rig->getAlignment();
    const int targetRoot = rig->getTargetRoot(), sourceRoot = rig->getSourceRoot();
    // A * R_s(b) * postRotation, skipping the products with an identity.
    auto followed = [&](const RetargetJointPlan& plan) {
        glm::dmat3 m = plan.sourceB >= 0 ? w.sourceRotations[static_cast<unsigned>(plan.sourceB)] : glm::dmat3(1.0);
        if (!aligned) m = multiply(alignment, m);
        return plan.postIsIdentity ? m : multiply(m, plan.postRotation);
    };
    const glm::dmat3 identity(1.0);
    numInexact = 0;
    for (unsigned t = 0; t < target.getNumJoints(); ++t)
    {
        const JointKinematics& k = target.getKinematics(t);
        const RetargetJointPlan& plan = plans[t];
        const int parent = target.getParent(t);
        const glm::dmat3& parentRotation = parent < 0 ? identity : w.targetRotations[static_cast<unsigned>(parent)];
        const bool parentExact = parent < 0 || w.targetExact[static_cast<unsigned>(parent)] != 0;
        if (k.hasTranslation)
            for (unsigned axis = 0; axis < 3; ++axis)
                if (k.translationDof[axis] >= 0)
                    targetValues[k.translationDof[axis]] = rest[static_cast<unsigned>(k.translationDof[axis])];

        glm::dmat3& rotation = w.targetRotations[t];
        bool exact = false;
        bool fitted = false;
        if (plan.kind == RetargetJointKind::Rest)
        {
            for (unsigned r = 0; r < k.numRotations; ++r) targetValues[k.rotationDof[r]] = rest[k.rotationDof[r]];
            rotation = multiply(parentRotation, restLocals[t]);
            fitted = true;
        }
        else if (plan.kind == RetargetJointKind::Copy && parentExact)
        {
            // The same local frames as the source joint's: its angles, turned or clamped into the limits.
            const JointKinematics& sk = source.getKinematics(static_cast<unsigned>(plan.sourceB));
            bool clamped = false;
            for (unsigned r = 0; r < k.numRotations; ++r)
            {
                const unsigned dof = k.rotationDof[r];
                const double angle = sourceValues[sk.rotationDof[r]];
                double& value = targetValues[dof];
                if (!turnWithinLimits(angle, target.getDofRangeMin(dof), target.getDofRangeMax(dof), angle, value))
                {
                    value = fitAngleToLimits(angle, target.getDofRangeMin(dof), target.getDofRangeMax(dof), angle);
                    clamped = true;
                }
            }
            exact = !clamped;
            rotation = exact ? followed(plan) : parentRotation * targetOffsets[t] * jointRotation(k, targetValues);
            fitted = true;
        }
        if (!fitted)
        {
            glm::dmat3 desired;
            if (plan.weight == 1.0)
                desired = followed(plan);
            else
                desired = alignment *
                          glm::mat3_cast(glm::slerp(changeSinceRest(*rig, w, plan.sourceA),
                                                    changeSinceRest(*rig, w, plan.sourceB), plan.weight)) *
                          plan.postRotation;
            const glm::dmat3 frame = multiply(parentRotation, targetOffsets[t]);
            exact = fitJointRotationDofs(target, t, multiplyTransposed(frame, desired), targetValues);
            rotation = exact ? desired : multiply(frame, jointRotation(k, targetValues));
        }
        if (!exact && plan.kind != RetargetJointKind::Rest && k.numRotations > 0) ++numInexact;

        // The root goes where the source's root goes, scaled: its translation DOFs from the point in its parent's
        // frame, less its offset, turned back through whatever of its rotations acts on them.
        const glm::dvec3 parentPosition =
            parent < 0 ? glm::dvec3(0.0) : w.targetPositions[static_cast<unsigned>(parent)];
        glm::dvec3 origin(k.offset[3]);
        if (k.hasTranslation)
        {
            const glm::dmat3 localRotation = multiplyTransposed(parentRotation, rotation);
            if (static_cast<int>(t) == targetRoot && sourceRoot >= 0)
            {
                const glm::dvec3 goal = rig->mapPosition(w.sourcePositions[static_cast<unsigned>(sourceRoot)]);
                const glm::dvec3 inParent = glm::transpose(parentRotation) * (goal - parentPosition) - origin;
                const glm::dvec3 slide =
                    glm::transpose(k.translationMode == TranslationMode::BeforeRotation ? targetOffsets[t]
                                                                                        : localRotation) *
                    inParent;
                for (unsigned axis = 0; axis < 3; ++axis)
                    if (k.translationDof[axis] >= 0)
                    {
                        const unsigned dof = static_cast<unsigned>(k.translationDof[axis]);
                        targetValues[dof] = target.clampToLimits(dof, slide[axis]);
                    }
            }
            origin = jointOrigin(k, targetOffsets[t], localRotation, targetValues);
        }
        w.targetPositions[t] = parentPosition + parentRotation * origin;
        w.targetExact[t] = exact ? 1 : 0;
    }
    return true;
}

} // namespace osgActor
