// ozz-animation's SkinningJob on osgActor's benchmark meshes and matrices (built only where CMake found ozz): the
// same vertices (in the skin's grouped order, which ozz writes in place, with no output index), the same joints and
// weights (ozz reads the first influences - 1 weights of each vertex and restores the last one from their sum), the
// same skinning matrices.
#include "SkinBenchMesh"

#include <ozz/base/maths/simd_math.h>
#include <ozz/base/span.h>
#include <ozz/geometry/runtime/skinning_job.h>

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace bench {

namespace {

std::vector<ozz::math::Float4x4> toOzz(const std::vector<glm::mat4>& matrices)
{
    std::vector<ozz::math::Float4x4> result(matrices.size());
    for (std::size_t j = 0; j < matrices.size(); ++j)
        for (int c = 0; c < 4; ++c) result[j].cols[c] = ozz::math::simd_float4::LoadPtrU(&matrices[j][c][0]);
    return result;
}

void BM_OzzSkinningJob(benchmark::State& state, SkinBenchCase config)
{
    const unsigned numVertices = static_cast<unsigned>(state.range(0));
    const osgActor::SkinPtr skin = makeSkin(numVertices, config.influences, config.method);
    const osgActor::SkinVertices vertices = skin->getVertices();
    const SkinBenchPose pose;
    const std::vector<ozz::math::Float4x4> matrices = toOzz(pose.matrices);
    const std::vector<ozz::math::Float4x4> normalMatrices = toOzz(pose.normalMatrices);
    std::vector<float> positions(3 * numVertices), normals(3 * numVertices), tangents(3 * numVertices);

    const unsigned k = config.influences;
    ozz::geometry::SkinningJob job;
    job.vertex_count = static_cast<int>(numVertices);
    job.influences_count = static_cast<int>(k);
    job.joint_matrices = ozz::span<const ozz::math::Float4x4>(matrices.data(), matrices.size());
    if (config.inverseTranspose)
        job.joint_inverse_transpose_matrices =
            ozz::span<const ozz::math::Float4x4>(normalMatrices.data(), normalMatrices.size());
    job.joint_indices = ozz::span<const uint16_t>(vertices.joints.data(), vertices.joints.size());
    job.joint_indices_stride = sizeof(uint16_t) * k;
    if (k > 1)
    {
        job.joint_weights = ozz::span<const float>(vertices.weights.data(), vertices.weights.size());
        job.joint_weights_stride = sizeof(float) * k;
    }
    job.in_positions = ozz::span<const float>(&vertices.positions[0].x, 3 * numVertices);
    job.in_positions_stride = sizeof(float) * 3;
    job.out_positions = ozz::span<float>(positions.data(), positions.size());
    job.out_positions_stride = sizeof(float) * 3;
    if (config.normals)
    {
        job.in_normals = ozz::span<const float>(&vertices.normals[0].x, 3 * numVertices);
        job.in_normals_stride = sizeof(float) * 3;
        job.out_normals = ozz::span<float>(normals.data(), normals.size());
        job.out_normals_stride = sizeof(float) * 3;
    }
    if (config.tangents)
    {
        job.in_tangents = ozz::span<const float>(&vertices.tangents[0].x, 4 * numVertices);
        job.in_tangents_stride = sizeof(float) * 4;
        job.out_tangents = ozz::span<float>(tangents.data(), tangents.size());
        job.out_tangents_stride = sizeof(float) * 3;
    }
    if (!job.Validate()) state.SkipWithError("invalid ozz job");
    for (auto _ : state)
    {
        job.Run();
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * numVertices);
}

} // namespace

void registerOzzSkinning()
{
    for (const SkinBenchCase& config : skinBenchCases())
    {
        if (config.method != osgActor::SkinningMethod::LinearBlend) continue;
        for (const unsigned size : skinBenchSizes())
            benchmark::RegisterBenchmark((std::string("skin/ozz/") + config.name).c_str(), BM_OzzSkinningJob, config)
                ->Arg(size);
    }
}

} // namespace bench
