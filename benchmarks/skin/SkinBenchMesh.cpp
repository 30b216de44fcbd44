#include "SkinBenchMesh"

#include <osgActor/core/skin/SkinBuilder>

#include <glm/ext/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>

namespace bench {

namespace {

glm::vec3 randomUnit(std::mt19937& random)
{
    std::normal_distribution<float> normal;
    for (;;)
    {
        const glm::vec3 v(normal(random), normal(random), normal(random));
        const float length = std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
        if (length > 1e-3f) return v / length;
    }
}

} // namespace

osgActor::SkinPtr makeSkin(unsigned numVertices, unsigned influences, osgActor::SkinningMethod method)
{
    std::mt19937 random(numVertices * 16 + influences);
    std::uniform_real_distribution<float> coordinate(-1.0f, 1.0f);
    std::uniform_real_distribution<float> weight(0.05f, 1.0f);
    osgActor::SkinBuilder builder("bench");
    builder.setMethod(method);
    for (unsigned j = 0; j < kSkinJoints; ++j) builder.addJoint("j" + std::to_string(j));
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec4> tangents;
    for (unsigned v = 0; v < numVertices; ++v)
    {
        positions.push_back(glm::vec3(coordinate(random), coordinate(random), coordinate(random)));
        const glm::vec3 normal = randomUnit(random);
        const glm::vec3 other = randomUnit(random);
        const glm::vec3 tangent = glm::normalize(glm::cross(normal, other));
        normals.push_back(normal);
        tangents.push_back(glm::vec4(tangent, 1.0f));
        // The `influences` joints nearest this vertex's place along the skeleton, with random weights.
        const unsigned centre = static_cast<unsigned>(std::uint64_t(v) * kSkinJoints / numVertices);
        const unsigned first = std::min(centre > influences / 2 ? centre - influences / 2 : 0u, kSkinJoints - influences);
        for (unsigned k = 0; k < influences; ++k) builder.addInfluence(v, first + k, weight(random));
    }
    builder.setPositions(positions);
    builder.setNormals(normals);
    builder.setTangents(tangents);
    return builder.build().skin;
}

SkinBenchPose::SkinBenchPose()
{
    std::mt19937 random(64);
    std::uniform_real_distribution<double> angle(-1.0, 1.0);
    std::uniform_real_distribution<double> offset(-0.5, 0.5);
    for (unsigned j = 0; j < kSkinJoints; ++j)
    {
        const glm::dvec3 axis = glm::normalize(glm::dvec3(angle(random), angle(random), angle(random)) + 1e-3);
        model.push_back(glm::translate(glm::dmat4(1.0), glm::dvec3(offset(random), offset(random), offset(random))) *
                        glm::rotate(glm::dmat4(1.0), angle(random), axis));
        definitionJoints.push_back(j);
        inverseBinds.push_back(glm::dmat4(1.0));
    }
    matrices.resize(kSkinJoints);
    normalMatrices.resize(kSkinJoints);
    dualQuaternions.resize(kSkinJoints);
    osgActor::SkinningMatricesJob job;
    job.modelMatrices = model;
    job.definitionJoints = definitionJoints;
    job.inverseBindMatrices = inverseBinds;
    job.matrices = matrices;
    job.normalMatrices = normalMatrices;
    job.dualQuaternions = dualQuaternions;
    job.run();
}

} // namespace bench
