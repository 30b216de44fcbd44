#include <osgActor/core/skin/SkinningMatricesJob>

#include <osgActor/core/LocalToModelJob>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace osgActor {

namespace {

bool emptyOrSized(std::size_t size, std::size_t expected) { return size == 0 || size == expected; }

SkinDualQuaternion dualQuaternionOf(const glm::dmat4& skinning, double bindScale)
{
    // The linear part over the bind scale is a rotation (the builder checked the inverse bind matrices; model
    // matrices are rigid): its quaternion, and the translation column as it is, since
    // skinning x = rotation (bindScale x) + translation.
    glm::dquat rotation = glm::normalize(glm::quat_cast(glm::dmat3(skinning) / bindScale));
    if (rotation.w < 0.0) rotation = -rotation;
    const glm::dquat translation(0.0, skinning[3][0], skinning[3][1], skinning[3][2]);
    SkinDualQuaternion result;
    result.real = glm::quat(rotation);
    result.dual = glm::quat(0.5 * (translation * rotation));
    return result;
}

} // namespace

bool SkinningMatricesJob::validate() const
{
    const std::size_t numJoints = definitionJoints.size();
    if (inverseBindMatrices.size() != numJoints) return false;
    if (!emptyOrSized(matricesDouble.size(), numJoints) || !emptyOrSized(matrices.size(), numJoints) ||
        !emptyOrSized(normalMatrices.size(), numJoints) || !emptyOrSized(dualQuaternions.size(), numJoints))
        return false;
    if (matricesDouble.empty() && matrices.empty() && normalMatrices.empty() && dualQuaternions.empty()) return false;
    if (!dualQuaternions.empty() && !(std::isfinite(bindScale) && bindScale > 0.0)) return false;
    for (const std::uint32_t joint : definitionJoints)
        if (joint >= modelMatrices.size()) return false;
    return true;
}

bool SkinningMatricesJob::run() const
{
    if (!validate()) return false;
    for (std::size_t j = 0; j < definitionJoints.size(); ++j)
    {
        const glm::dmat4 skinning = multiplyAffine(modelMatrices[definitionJoints[j]], inverseBindMatrices[j]);
        if (!matricesDouble.empty()) matricesDouble[j] = skinning;
        if (!matrices.empty()) matrices[j] = glm::mat4(skinning);
        if (!normalMatrices.empty()) normalMatrices[j] = glm::mat4(glm::mat3(glm::inverseTranspose(glm::dmat3(skinning))));
        if (!dualQuaternions.empty()) dualQuaternions[j] = dualQuaternionOf(skinning, bindScale);
    }
    return true;
}

} // namespace osgActor
