#include <osgActor/core/ActorDefinition>
#include <osgActor/core/detail/JointBatches>

namespace osgActor {

namespace {

bool batchable(const JointKinematics& k) { return k.numRotations > 0 && !k.hasTranslation && k.offsetIsTranslation; }

} // namespace

JointBatchPlan planJointBatches(const std::vector<JointKinematics>& kinematics)
{
    JointBatchPlan plan;
    // Per rotation sequence, the batch still filling, or -1.
    int open[kNumRotationSequences];
    for (int& batch : open) batch = -1;
    for (std::uint32_t joint = 0; joint < kinematics.size(); ++joint)
    {
        const JointKinematics& k = kinematics[joint];
        if (!batchable(k))
        {
            plan.singleJoints.push_back(joint);
            continue;
        }
        int& current = open[k.rotationSequence];
        if (current < 0)
        {
            current = static_cast<int>(plan.batches.size());
            plan.batches.emplace_back();
            plan.batches.back().rotationSequence = k.rotationSequence;
        }
        JointBatch& batch = plan.batches[static_cast<unsigned>(current)];
        const unsigned lane = batch.numJoints++;
        // Filling from lane to the end keeps every unused lane a copy of a real joint.
        for (unsigned l = lane; l < JointBatch::kWidth; ++l)
        {
            batch.joints[l] = joint;
            for (unsigned r = 0; r < 3; ++r) batch.angleDofs[r][l] = k.rotationDof[r < k.numRotations ? r : 0];
        }
        if (batch.numJoints == JointBatch::kWidth) current = -1;
    }
    return plan;
}

} // namespace osgActor
