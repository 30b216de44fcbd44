#include <osgActor/core/ActorTransforms>
#include <osgActor/core/Dof>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>

namespace osgActor {

namespace {

/** T(translation) * R(rotation): a point of the frame is turned, then placed. */
glm::dmat4 turnThenPlace(const glm::dvec3& translation, const glm::dquat& rotation)
{
    return glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(glm::normalize(rotation));
}

} // namespace

glm::dmat4 computePreTransformMatrix(const ActorTransforms& t)
{
    return turnThenPlace(t.preTranslation, t.preRotation);
}

glm::dmat4 computePostTransformMatrix(const ActorTransforms& t)
{
    return turnThenPlace(t.postTranslation, t.postRotation);
}

glm::dmat4 computeActorMatrix(const ActorTransforms& t)
{
    return computePreTransformMatrix(t) * computePostTransformMatrix(t);
}

bool isValidTransformTranslation(const glm::dvec3& v)
{
    // Not just finite: two translations of 1e308 would overflow actor_m.
    return std::abs(v.x) <= kMaxDofMagnitude && std::abs(v.y) <= kMaxDofMagnitude && std::abs(v.z) <= kMaxDofMagnitude;
}

bool isValidTransformRotation(const glm::dquat& q)
{
    const double length2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    return std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) && std::isfinite(q.w) && length2 > 0.0 &&
           std::isfinite(length2);
}

} // namespace osgActor
