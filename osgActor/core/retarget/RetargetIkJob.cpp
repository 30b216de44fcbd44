#include <osgActor/core/retarget/RetargetIkJob>
#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/LocalToModelJob>
#include <osgActor/core/ik/IkSolve>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

bool RetargetIkJob::validate() const
{
    if (!rig || !limbs || !workspace || !workspace->fits(*rig)) return false;
    const std::size_t n = limbs->limbs.size();
    if (goals.size() != n || ikWorkspaces.size() != n || (!enabled.empty() && enabled.size() != n)) return false;
    if (targetDofs.size() != rig->getTargetDefinition()->getNumDofs()) return false;
    for (std::size_t i = 0; i < n; ++i)
        if (!limbs->limbs[i].chain || !ikWorkspaces[i].fits(*limbs->limbs[i].chain) || !goals[i].isValid())
            return false;
    return true;
}

namespace {

bool isBelow(const ActorDefinition& definition, unsigned joint, unsigned ancestor)
{
    for (int j = static_cast<int>(joint); j >= 0; j = definition.getParent(static_cast<unsigned>(j)))
        if (static_cast<unsigned>(j) == ancestor) return true;
    return false;
}

} // namespace

double RetargetIkJob::lowerRootForLegs()
{
    const ActorDefinition& target = *rig->getTargetDefinition();
    const int root = rig->getTargetRoot();
    if (root < 0 || !target.getKinematics(static_cast<unsigned>(root)).hasTranslation) return 0.0;
    double drop = 0.0;
    for (std::size_t i = 0; i < limbs->limbs.size(); ++i)
    {
        const RetargetLimb& limb = limbs->limbs[i];
        if (!limb.isLeg || (!enabled.empty() && !enabled[i])) continue;
        const unsigned hip = limb.chain->getRootJoint();
        if (!isBelow(target, hip, static_cast<unsigned>(root))) continue;
        // Lowered by d the hip is at hip - d z: |goal - hip + d z| = reach, below the hip.
        const glm::dvec3 toGoal = goals[i].position - workspace->targetPosition(hip);
        const double reach = 0.999 * limb.chain->getLength();
        const double across2 = toGoal.x * toGoal.x + toGoal.y * toGoal.y;
        if (glm::dot(toGoal, toGoal) <= reach * reach) continue;
        const double needed = across2 < reach * reach ? -toGoal.z - std::sqrt(reach * reach - across2) : -toGoal.z;
        drop = std::max(drop, needed);
    }
    if (!(drop > 0.0)) return 0.0;
    // The root's translation DOFs moved by -drop along the model's Z, through the frame they slide in.
    const unsigned r = static_cast<unsigned>(root);
    const JointKinematics& k = target.getKinematics(r);
    const int parent = target.getParent(r);
    const glm::dmat3 parentRotation =
        parent < 0 ? glm::dmat3(1.0) : workspace->targetRotation(static_cast<unsigned>(parent));
    const glm::dmat3 slideFrame = k.translationMode == TranslationMode::BeforeRotation
                                      ? parentRotation * rig->getTargetOffsetRotations()[r]
                                      : workspace->targetRotation(r);
    const glm::dvec3 slide = glm::transpose(slideFrame) * glm::dvec3(0.0, 0.0, -drop);
    for (unsigned axis = 0; axis < 3; ++axis)
        if (k.translationDof[axis] >= 0)
        {
            const unsigned dof = static_cast<unsigned>(k.translationDof[axis]);
            targetDofs[dof] = target.clampToLimits(dof, targetDofs[dof] + slide[axis]);
        }
    return drop;
}

bool RetargetIkJob::run()
{
    if (!validate()) return false;
    const ActorDefinition& target = *rig->getTargetDefinition();
    largestError = 0.0;
    rootDrop = lowerRoot ? lowerRootForLegs() : 0.0;
    const glm::dvec3 drop(0.0, 0.0, -rootDrop);
    const int root = rig->getTargetRoot();
    for (std::size_t i = 0; i < limbs->limbs.size(); ++i)
    {
        if (!enabled.empty() && !enabled[i]) continue;
        const RetargetLimb& limb = limbs->limbs[i];
        const IkChain& chain = *limb.chain;
        const int rootParent = target.getParent(chain.getRootJoint());
        const bool belowRoot = root >= 0 && isBelow(target, chain.getRootJoint(), static_cast<unsigned>(root));
        glm::dmat4 rootParentModel(1.0);
        if (rootParent >= 0)
        {
            rootParentModel = workspace->targetModels[static_cast<unsigned>(rootParent)];
            if (belowRoot) rootParentModel[3] += glm::dvec4(drop, 0.0);
        }
        IkGoal goal = goals[i];
        if (!limb.isLeg && belowRoot) goal.position += drop;
        IkJob job;
        job.definition = &target;
        job.chain = &chain;
        job.goal = &goal;
        job.rootParentModel = rootParentModel;
        job.dofs = targetDofs.data();
        job.workspace = &ikWorkspaces[i];
        if (!solveIk(job)) continue;
        largestError = std::max(largestError, job.result.positionError);

        // The end joint's model rotation as the retargeting made it, under the solved limb.
        glm::dmat4 model = rootParentModel;
        for (unsigned c = 0; c + 1 < chain.getNumJoints(); ++c)
            model = multiplyAffine(model,
                                   computeJointMatrix(target.getKinematics(chain.getJoint(c)), targetDofs.data()));
        const unsigned end = chain.getEffectorJoint();
        const glm::dmat3 frame = glm::dmat3(model) * rig->getTargetOffsetRotations()[end];
        fitJointRotationDofs(target, end, glm::transpose(frame) * workspace->targetRotation(end), targetDofs.data());
    }
    return true;
}

} // namespace osgActor
