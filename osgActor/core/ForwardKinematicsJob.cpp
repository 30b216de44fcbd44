#include <osgActor/core/ForwardKinematicsJob>

#include <cmath>

namespace osgActor {

namespace {

/** m = m * R_axis(angle), for a 3x3 rotation held in the upper-left of a dmat4 (columns 0..2). Multiplying on
  * the right mixes two columns only, so this is four multiply-adds rather than a matrix product. */
inline void postRotate(glm::dmat4& m, unsigned axis, double angle)
{
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    // For X the mixed columns are (Y, Z); for Y (Z, X); for Z (X, Y): col_i' = c col_i + s col_j,
    // col_j' = -s col_i + c col_j. Row 3 is (0, 0, 0) in these columns and stays so.
    const unsigned i = (axis + 1) % 3;
    const unsigned j = (axis + 2) % 3;
    const glm::dvec4 ci = m[i];
    const glm::dvec4 cj = m[j];
    m[i] = c * ci + s * cj;
    m[j] = -s * ci + c * cj;
}

} // namespace

glm::dmat4 computeJointMatrix(const JointKinematics& k, const double* dofs)
{
    // articulation = R_a1 * R_a2 * R_a3, then the translation DOFs (see the header for where they act).
    glm::dmat4 articulation(1.0);
    for (unsigned r = 0; r < k.numRotations; ++r) postRotate(articulation, k.rotationAxis[r], dofs[k.rotationDof[r]]);

    glm::dvec3 t(0.0);
    for (unsigned axis = 0; axis < 3; ++axis)
        if (k.translationDof[axis] >= 0) t[axis] = dofs[k.translationDof[axis]];
    const glm::dvec3 slide =
        k.translationMode == TranslationMode::AfterRotation ? glm::dvec3(articulation * glm::dvec4(t, 0.0)) : t;
    articulation[3] = glm::dvec4(slide, 1.0);

    if (k.offsetIsTranslation)
    {
        articulation[3] += glm::dvec4(glm::dvec3(k.offset[3]), 0.0);
        return articulation;
    }
    return k.offset * articulation;
}

bool ForwardKinematicsJob::validate() const
{
    if (!definition || !jointDirty || !local || !model || !localChanged || !modelChanged) return false;
    return dofs != nullptr || definition->getNumDofs() == 0;
}

bool ForwardKinematicsJob::run()
{
    numRecomputed = 0;
    if (!validate()) return false;
    const unsigned numJoints = definition->getNumJoints();
    const std::vector<JointKinematics>& kinematics = definition->getAllKinematics();
    const std::vector<int>& parents = definition->getParents();
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const bool localDirty = jointDirty[j] != 0;
        if (localDirty)
        {
            local[j] = computeJointMatrix(kinematics[j], dofs);
            jointDirty[j] = 0;
            localChanged[j] = 1;
            ++numRecomputed;
        }
        const int parent = parents[j];
        // Parents come first, so modelChanged[parent] is already final for this run.
        const bool moved = localDirty || (parent >= 0 && modelChanged[parent]);
        modelChanged[j] = moved ? 1 : 0;
        if (moved) model[j] = parent >= 0 ? model[parent] * local[j] : local[j];
    }
    return true;
}

} // namespace osgActor
