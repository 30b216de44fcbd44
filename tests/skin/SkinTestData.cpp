#include "SkinTestData"

#include <osgActor/core/ActorDefinitionBuilder>

#include <glm/ext/matrix_double3x3.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

namespace osgActor {
namespace test {

namespace {

glm::dvec3 randomUnitVector(std::mt19937& random)
{
    std::normal_distribution<double> normal;
    for (;;)
    {
        const glm::dvec3 v(normal(random), normal(random), normal(random));
        const double length = glm::length(v);
        if (length > 1e-3) return v / length;
    }
}

/** Any unit vector perpendicular to u. */
glm::dvec3 perpendicularTo(const glm::dvec3& u)
{
    const glm::dvec3 other = std::abs(u.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(u, other));
}

std::vector<glm::dmat4> restModelMatrices(const ActorDefinitionPtr& definition)
{
    ActorPose rest(definition);
    rest.updateMatrices();
    std::vector<glm::dmat4> model;
    for (unsigned j = 0; j < rest.getNumJoints(); ++j) model.push_back(rest.getModelMatrix(j));
    return model;
}

} // namespace

SkinBuilder SkinSource::toBuilder(const std::string& name, SkinningMethod method) const
{
    SkinBuilder builder(name);
    builder.setMethod(method);
    for (std::size_t j = 0; j < jointNames.size(); ++j) builder.addJoint(jointNames[j], inverseBindMatrices[j]);
    builder.setPositions(positions);
    builder.setNormals(normals);
    builder.setTangents(tangents);
    for (std::size_t v = 0; v < influences.size(); ++v)
        for (const auto& influence : influences[v])
            builder.addInfluence(static_cast<unsigned>(v), influence.first, static_cast<float>(influence.second));
    return builder;
}

double SkinSource::diagonal() const
{
    glm::dvec3 low(positions[0]), high(positions[0]);
    for (const glm::vec3& p : positions)
    {
        low = glm::min(low, glm::dvec3(p));
        high = glm::max(high, glm::dvec3(p));
    }
    return glm::length(high - low);
}

ActorDefinitionPtr makeRandomDefinition(unsigned numJoints, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> length(0.05, 0.3);
    std::uniform_real_distribution<double> angle(-3.0, 3.0);
    ActorDefinitionBuilder builder("random");
    for (unsigned j = 0; j < numJoints; ++j)
    {
        const std::string parent = j == 0 ? std::string() : "j" + std::to_string(random() % j);
        const glm::dvec3 axis = randomUnitVector(random);
        builder.addJoint("j" + std::to_string(j), parent)
            .offset(j == 0 ? glm::dvec3(0.0) : randomUnitVector(random) * length(random))
            .rotation(angle(random), axis.x, axis.y, axis.z)
            .dofs(j == 0 ? kRotationDofs | Dof::TX | Dof::TY | Dof::TZ : kRotationDofs);
    }
    return builder.build().definition;
}

ActorPose makeRandomPose(const ActorDefinitionPtr& definition, std::uint32_t seed)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> value(-1.0, 1.0);
    ActorPose pose(definition);
    for (unsigned d = 0; d < pose.getNumDofs(); ++d) pose.setDof(d, value(random));
    pose.updateMatrices();
    return pose;
}

SkinSource makeRandomSkin(const ActorDefinition& definition, unsigned numVertices, unsigned influences,
                          std::uint32_t seed, double bindScale)
{
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> coordinate(-0.5, 0.5);
    std::uniform_real_distribution<double> weight(0.05, 1.0);
    SkinSource source;
    ActorDefinitionPtr shared(&definition, [](const ActorDefinition*) {});
    const std::vector<glm::dmat4> rest = restModelMatrices(shared);
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
    {
        source.jointNames.push_back(definition.getJointName(j));
        source.inverseBindMatrices.push_back(glm::inverse(rest[j]) * glm::scale(glm::dmat4(1.0), glm::dvec3(bindScale)));
    }
    std::vector<unsigned> joints(definition.getNumJoints());
    for (unsigned v = 0; v < numVertices; ++v)
    {
        source.positions.push_back(glm::vec3(coordinate(random), coordinate(random), coordinate(random)));
        const glm::dvec3 normal = randomUnitVector(random);
        const glm::dvec3 tangent = glm::normalize(glm::cross(normal, randomUnitVector(random)));
        source.normals.push_back(glm::vec3(normal));
        source.tangents.push_back(glm::vec4(glm::vec3(tangent), random() % 2 ? 1.0f : -1.0f));
        std::iota(joints.begin(), joints.end(), 0u);
        std::shuffle(joints.begin(), joints.end(), random);
        std::vector<std::pair<unsigned, double>> vertexInfluences;
        double sum = 0.0;
        for (unsigned k = 0; k < influences; ++k)
        {
            // Weights that floats hold exactly, so that the builder's renormalisation leaves them as they are.
            const double w = std::round(weight(random) * 1024.0) / 1024.0;
            vertexInfluences.push_back({joints[k], w});
            sum += w;
        }
        for (auto& influence : vertexInfluences) influence.second /= sum;
        source.influences.push_back(vertexInfluences);
    }
    return source;
}

SkinSource makeTubeSkin(const ActorDefinition& definition, unsigned rings, unsigned sides, double radiusPerLength,
                        double minLength)
{
    SkinSource source;
    ActorDefinitionPtr shared(&definition, [](const ActorDefinition*) {});
    const std::vector<glm::dmat4> rest = restModelMatrices(shared);
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
    {
        source.jointNames.push_back(definition.getJointName(j));
        source.inverseBindMatrices.push_back(glm::inverse(rest[j]));
    }
    const double pi = std::acos(-1.0);
    for (unsigned j = 0; j < definition.getNumJoints(); ++j)
    {
        const int parent = definition.getParent(j);
        if (parent < 0) continue;
        const glm::dvec3 from(rest[parent][3]);
        const glm::dvec3 to(rest[j][3]);
        const double length = glm::length(to - from);
        if (length < minLength) continue;
        const glm::dvec3 along = (to - from) / length;
        const glm::dvec3 side = perpendicularTo(along);
        const glm::dvec3 up = glm::cross(along, side);
        const int grandparent = definition.getParent(static_cast<unsigned>(parent));
        int child = -1;
        for (unsigned c = j + 1; c < definition.getNumJoints() && child < 0; ++c)
            if (definition.getParent(c) == static_cast<int>(j)) child = static_cast<int>(c);
        for (unsigned ring = 0; ring < rings; ++ring)
        {
            const double s = (ring + 0.5) / rings;
            // The bone's own joint is its parent's frame; near the upper end the joint above blends in (and the one
            // above that, a little), near the lower end the joint at its tip (and that joint's first child).
            std::vector<std::pair<unsigned, double>> influences{{static_cast<unsigned>(parent), 1.0}};
            if (s < 0.3 && grandparent >= 0)
            {
                const double w = 0.5 * (0.3 - s) / 0.3;
                influences.push_back({static_cast<unsigned>(grandparent), w});
                const int above = definition.getParent(static_cast<unsigned>(grandparent));
                if (above >= 0) influences.push_back({static_cast<unsigned>(above), 0.25 * w});
            }
            if (s > 0.7)
            {
                const double w = 0.5 * (s - 0.7) / 0.3;
                influences.push_back({j, w});
                if (child >= 0) influences.push_back({static_cast<unsigned>(child), 0.25 * w});
            }
            double sum = 0.0;
            for (const auto& influence : influences) sum += influence.second;
            for (auto& influence : influences) influence.second /= sum;
            for (unsigned k = 0; k < sides; ++k)
            {
                const double theta = 2.0 * pi * k / sides;
                const glm::dvec3 outward = std::cos(theta) * side + std::sin(theta) * up;
                source.positions.push_back(glm::vec3(from + s * length * along + radiusPerLength * length * outward));
                source.normals.push_back(glm::vec3(outward));
                source.tangents.push_back(glm::vec4(glm::vec3(along), 1.0f));
                source.influences.push_back(influences);
            }
        }
    }
    return source;
}

std::vector<glm::dmat4> referenceSkinningMatrices(const ActorPose& pose, const SkinSource& source)
{
    std::vector<glm::dmat4> matrices;
    const ActorDefinition& definition = *pose.getDefinition();
    for (std::size_t j = 0; j < source.jointNames.size(); ++j)
        matrices.push_back(pose.getModelMatrix(static_cast<unsigned>(definition.findJoint(source.jointNames[j]))) *
                           source.inverseBindMatrices[j]);
    return matrices;
}

std::vector<ReferenceVertex> referenceLinearBlend(const SkinSource& source, const std::vector<glm::dmat4>& matrices,
                                                  bool inverseTranspose)
{
    std::vector<ReferenceVertex> result(source.positions.size());
    for (std::size_t v = 0; v < source.positions.size(); ++v)
    {
        ReferenceVertex out{glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
        for (const auto& influence : source.influences[v])
        {
            const glm::dmat4& m = matrices[influence.first];
            const double w = influence.second;
            const glm::dmat3 linear(m);
            const glm::dmat3 normalMatrix = inverseTranspose ? glm::inverseTranspose(linear) : linear;
            out.position += w * glm::dvec3(m * glm::dvec4(glm::dvec3(source.positions[v]), 1.0));
            if (!source.normals.empty()) out.normal += w * (normalMatrix * glm::dvec3(source.normals[v]));
            if (!source.tangents.empty()) out.tangent += w * (linear * glm::dvec3(source.tangents[v]));
        }
        result[v] = out;
    }
    return result;
}

std::vector<ReferenceVertex> referenceDualQuaternion(const SkinSource& source, const std::vector<glm::dmat4>& matrices,
                                                     double bindScale)
{
    // Each joint's rigid motion as (rotation quaternion, dual part).
    std::vector<glm::dquat> real, dual;
    for (const glm::dmat4& m : matrices)
    {
        const glm::dquat r = glm::normalize(glm::quat_cast(glm::dmat3(m) / bindScale));
        real.push_back(r);
        dual.push_back(0.5 * glm::dquat(0.0, m[3][0], m[3][1], m[3][2]) * r);
    }
    std::vector<ReferenceVertex> result(source.positions.size());
    for (std::size_t v = 0; v < source.positions.size(); ++v)
    {
        // The joint whose hemisphere the others are taken on: the largest weight (the lower joint on a tie).
        unsigned first = source.influences[v][0].first;
        double firstWeight = source.influences[v][0].second;
        for (const auto& influence : source.influences[v])
            if (influence.second > firstWeight || (influence.second == firstWeight && influence.first < first))
            {
                first = influence.first;
                firstWeight = influence.second;
            }
        glm::dquat blendedReal(0.0, 0.0, 0.0, 0.0), blendedDual(0.0, 0.0, 0.0, 0.0);
        for (const auto& influence : source.influences[v])
        {
            const double sign = glm::dot(real[influence.first], real[first]) < 0.0 ? -1.0 : 1.0;
            blendedReal = blendedReal + (sign * influence.second) * real[influence.first];
            blendedDual = blendedDual + (sign * influence.second) * dual[influence.first];
        }
        const double length = glm::length(blendedReal);
        const glm::dquat r = blendedReal / length;
        const glm::dquat d = blendedDual / length;
        const glm::dquat translation = 2.0 * d * glm::conjugate(r);
        ReferenceVertex out;
        out.position = r * (bindScale * glm::dvec3(source.positions[v])) +
                       glm::dvec3(translation.x, translation.y, translation.z);
        if (!source.normals.empty()) out.normal = r * glm::dvec3(source.normals[v]);
        if (!source.tangents.empty()) out.tangent = r * glm::dvec3(source.tangents[v]);
        result[v] = out;
    }
    return result;
}

} // namespace test
} // namespace osgActor
