// Internal to the library (not installed): a skeleton's model matrices for one DOF vector, by the core's forward
// kinematics, for the retargeting's set-up (RetargetRig's rest poses, JointMapGuess's rest skeleton); the per-frame
// job keeps its buffers in its workspace instead.
#ifndef OSGACTOR_CORE_RETARGET_MODELMATRICES_H
#define OSGACTOR_CORE_RETARGET_MODELMATRICES_H 1

#include <osgActor/core/ActorDefinition>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/LocalToModelJob>

#include <glm/ext/matrix_double4x4.hpp>

#include <cstdint>
#include <vector>

namespace osgActor {
namespace retarget_detail {

/** Per joint, its model matrix (the joint frame in the skeleton's frame, model space, model units) for dofs (the whole
  * DOF vector, radians and model units): LocalMatricesJob then LocalToModelJob, every joint. */
inline std::vector<glm::dmat4> computeModelMatrices(const ActorDefinition& definition, const std::vector<double>& dofs)
{
    const unsigned numJoints = definition.getNumJoints();
    std::vector<glm::dmat4> locals(numJoints, glm::dmat4(1.0)), models(numJoints, glm::dmat4(1.0));
    std::vector<double*> localPointers(numJoints);
    for (unsigned j = 0; j < numJoints; ++j) localPointers[j] = &locals[j][0][0];
    std::vector<std::uint8_t> dirty(numJoints, 1), localChanged(numJoints, 0), modelStale(numJoints, 0);
    LocalMatricesJob local;
    local.definition = &definition;
    local.dofs = dofs;
    local.jointDirty = dirty;
    local.local = localPointers;
    local.localChanged = localChanged;
    local.modelStale = modelStale;
    local.run();
    LocalToModelJob toModel;
    toModel.parents = definition.getParents();
    toModel.local = Span<const double* const>(localPointers.data(), numJoints);
    toModel.model = models;
    toModel.run();
    return models;
}

} // namespace retarget_detail
} // namespace osgActor

#endif
