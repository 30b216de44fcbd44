// The pose alone against ozz-animation, side by side: ozz's SamplingJob and LocalToModelJob, and osgActor's
// ClipPlayer and forward kinematics (as osgactor_core_bench), on the same 31-joint humanoid and the same key
// frames, interleaved per N in one run. Issue 7 states its pose target against ozz-animation; ozz is no Debian
// package, so this benchmark is built only where CMake finds an installed ozz (OSGACTOR_OZZ_ROOT, see
// docs/performance.md).
#include "BenchHumanoid"
#include "NsPerJoint"
#include "PoseCrowd"

#include <osgActor/core/ActorPose>
#include <osgActor/core/ClipPlayer>

#include <ozz/animation/offline/animation_builder.h>
#include <ozz/animation/offline/animation_optimizer.h>
#include <ozz/animation/offline/raw_animation.h>
#include <ozz/animation/offline/raw_skeleton.h>
#include <ozz/animation/offline/skeleton_builder.h>
#include <ozz/animation/runtime/animation.h>
#include <ozz/animation/runtime/local_to_model_job.h>
#include <ozz/animation/runtime/sampling_job.h>
#include <ozz/animation/runtime/skeleton.h>
#include <ozz/base/maths/simd_math.h>
#include <ozz/base/maths/soa_transform.h>

#include <benchmark/benchmark.h>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace offline = ozz::animation::offline;

/** The humanoid as ozz sees it, with the clip's key frames taken from osgActor's own local matrices (so both systems
  * interpolate between exactly the same rotations), and where each ozz joint is in the bench's joint list. */
struct OzzHumanoid
{
    ozz::unique_ptr<ozz::animation::Skeleton> skeleton;
    ozz::unique_ptr<ozz::animation::Animation> animation;
    std::vector<unsigned> benchJoint; // per ozz joint
};

void addChildren(offline::RawSkeleton::Joint& parent, int parentIndex)
{
    const std::vector<bench::BenchJoint>& joints = bench::humanoidJoints();
    for (unsigned j = 0; j < joints.size(); ++j)
        if (joints[j].parent == parentIndex)
        {
            parent.children.emplace_back();
            offline::RawSkeleton::Joint& child = parent.children.back();
            child.name = joints[j].name.c_str();
            child.transform = ozz::math::Transform::identity();
            addChildren(child, static_cast<int>(j));
        }
}

/** The local matrix of every bench joint at every key frame of the clip, from osgActor's forward kinematics. */
std::vector<std::vector<glm::dmat4>> keyFrameLocals()
{
    const bench::BenchClip& clip = bench::humanoidClip();
    osgActor::ActorPose pose(bench::humanoidDefinition());
    const osgActor::ActorDefinition& def = *pose.getDefinition();
    std::vector<std::vector<glm::dmat4>> locals(clip.numFrames);
    for (unsigned f = 0; f < clip.numFrames; ++f)
    {
        for (unsigned j = 0; j < clip.jointCount; ++j)
            for (unsigned a = 0; a < 3; ++a)
                pose.setDof(def.getFirstDof(j) + a, clip.anglesAt(f, j)[a]);
        for (unsigned a = 0; a < 3; ++a) pose.setDof(def.getFirstDof(0) + 3 + a, clip.rootPosition[f * 3 + a]);
        pose.updateLocalMatrices();
        for (unsigned j = 0; j < clip.jointCount; ++j) locals[f].push_back(pose.getLocalMatrix(j));
    }
    return locals;
}

/** optimized: the key frames decimated by ozz's AnimationOptimizer at its default tolerance (1 mm at 10 cm), as
  * ozz's own pipeline does; otherwise every key frame of the clip, the same keys as osgActor's. */
OzzHumanoid buildOzzHumanoid(bool optimized)
{
    OzzHumanoid humanoid;
    const std::vector<bench::BenchJoint>& joints = bench::humanoidJoints();
    offline::RawSkeleton raw;
    raw.roots.emplace_back();
    raw.roots[0].name = joints[0].name.c_str();
    raw.roots[0].transform = ozz::math::Transform::identity();
    addChildren(raw.roots[0], 0);
    humanoid.skeleton = offline::SkeletonBuilder()(raw);

    std::map<std::string, unsigned> benchIndex;
    for (unsigned j = 0; j < joints.size(); ++j) benchIndex[joints[j].name] = j;
    const bench::BenchClip& clip = bench::humanoidClip();
    const std::vector<std::vector<glm::dmat4>> locals = keyFrameLocals();
    offline::RawAnimation animation;
    animation.duration = static_cast<float>(clip.duration());
    animation.tracks.resize(static_cast<std::size_t>(humanoid.skeleton->num_joints()));
    for (int t = 0; t < humanoid.skeleton->num_joints(); ++t)
    {
        const unsigned j = benchIndex.at(humanoid.skeleton->joint_names()[t]);
        humanoid.benchJoint.push_back(j);
        offline::RawAnimation::JointTrack& track = animation.tracks[static_cast<std::size_t>(t)];
        for (unsigned f = 0; f < clip.numFrames; ++f)
        {
            const float time = static_cast<float>(f / clip.framesPerSecond);
            const glm::dmat4& m = locals[f][j];
            const glm::dquat q = glm::quat_cast(glm::dmat3(m));
            track.rotations.push_back({time, ozz::math::Quaternion(static_cast<float>(q.x), static_cast<float>(q.y),
                                                                   static_cast<float>(q.z), static_cast<float>(q.w))});
            // Only the root moves; every other joint keeps its offset, one key as an ozz user would store it.
            if (j == 0 || f == 0)
                track.translations.push_back({time, ozz::math::Float3(static_cast<float>(m[3][0]),
                                                                      static_cast<float>(m[3][1]),
                                                                      static_cast<float>(m[3][2]))});
        }
        track.scales.push_back({0.0f, ozz::math::Float3::one()});
    }
    if (optimized)
    {
        offline::RawAnimation decimated;
        offline::AnimationOptimizer()(animation, *humanoid.skeleton, &decimated);
        animation = decimated;
    }
    humanoid.animation = offline::AnimationBuilder()(animation);
    return humanoid;
}

const OzzHumanoid& ozzHumanoid(bool optimized = false)
{
    static const OzzHumanoid humanoid = buildOzzHumanoid(false);
    static const OzzHumanoid decimated = buildOzzHumanoid(true);
    return optimized ? decimated : humanoid;
}

/** One ozz instance: its sampling context and its local (SoA) and model transforms. */
struct OzzInstance
{
    ozz::animation::SamplingJob::Context context;
    ozz::vector<ozz::math::SoaTransform> locals;
    ozz::vector<ozz::math::Float4x4> models;
};

bool runOzz(const OzzHumanoid& humanoid, OzzInstance& instance, float time)
{
    const float duration = humanoid.animation->duration();
    ozz::animation::SamplingJob sampling;
    sampling.animation = humanoid.animation.get();
    sampling.context = &instance.context;
    sampling.ratio = std::fmod(time, duration) / duration;
    sampling.output = ozz::make_span(instance.locals);
    ozz::animation::LocalToModelJob localToModel;
    localToModel.skeleton = humanoid.skeleton.get();
    localToModel.input = ozz::make_span(instance.locals);
    localToModel.output = ozz::make_span(instance.models);
    return sampling.Run() && localToModel.Run();
}

/** Largest difference between ozz's and osgActor's model matrices of every joint at key frame `frame`, where both
  * hold exactly the key's rotations: checks that the two systems are given the same skeleton and motion. */
double modelMatrixMismatchAtKeyFrame(unsigned frame)
{
    const OzzHumanoid& humanoid = ozzHumanoid();
    OzzInstance instance;
    instance.context.Resize(humanoid.skeleton->num_joints());
    instance.locals.resize(static_cast<std::size_t>(humanoid.skeleton->num_soa_joints()));
    instance.models.resize(static_cast<std::size_t>(humanoid.skeleton->num_joints()));
    const double time = frame / bench::humanoidClip().framesPerSecond;
    if (!runOzz(humanoid, instance, static_cast<float>(time))) return INFINITY;

    osgActor::ActorPose pose(bench::humanoidDefinition());
    auto player = std::make_shared<osgActor::ClipPlayer>(bench::humanoidOsgActorClip());
    player->seek(time);
    player->play();
    const std::vector<osgActor::ControllerPtr> players{player};
    osgActor::ActorTransforms transforms;
    osgActor::ControllerTarget target{pose, transforms};
    osgActor::runControllers(players, osgActor::ControllerContext(), target);
    pose.updateMatrices();

    double worst = 0.0;
    for (std::size_t t = 0; t < instance.models.size(); ++t)
    {
        const glm::dmat4& expected = pose.getModelMatrix(humanoid.benchJoint[t]);
        float columns[4][4];
        for (int c = 0; c < 4; ++c) ozz::math::StorePtrU(instance.models[t].cols[c], columns[c]);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) worst = std::max(worst, std::fabs(columns[c][r] - expected[c][r]));
    }
    return worst;
}

bool sameMotion(benchmark::State& state)
{
    static const double mismatch = std::max(modelMatrixMismatchAtKeyFrame(7), modelMatrixMismatchAtKeyFrame(44));
    // ozz keeps its rotation keys quantized to 16 bits a component: up to about a millimetre at the humanoid's
    // finger tips. A skeleton or rotation convention given wrongly is off by decimetres.
    if (mismatch <= 2e-3) return true;
    state.SkipWithError(("ozz and osgActor disagree at key frames by " + std::to_string(mismatch)).c_str());
    return false;
}

void BM_PoseAlone_ozz(benchmark::State& state, bool optimized)
{
    if (!sameMotion(state)) return;
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    const OzzHumanoid& humanoid = ozzHumanoid(optimized);
    std::vector<OzzInstance> instances(numActors);
    for (OzzInstance& instance : instances)
    {
        instance.context.Resize(humanoid.skeleton->num_joints());
        instance.locals.resize(static_cast<std::size_t>(humanoid.skeleton->num_soa_joints()));
        instance.models.resize(static_cast<std::size_t>(humanoid.skeleton->num_joints()));
    }
    float time = 0.0f;
    for (auto _ : state)
    {
        time += 1.0f / 60.0f;
        for (unsigned a = 0; a < numActors; ++a)
            if (!runOzz(humanoid, instances[a], time + 0.01f * static_cast<float>(a)))
            {
                state.SkipWithError("ozz job failed");
                return;
            }
        benchmark::ClobberMemory();
    }
    bench::reportNsPerJoint(state, numActors);
}

void BM_PoseAlone_osgActor(benchmark::State& state)
{
    if (!sameMotion(state)) return;
    const unsigned numActors = static_cast<unsigned>(state.range(0));
    bench::PoseCrowd crowd(numActors);
    for (auto _ : state)
    {
        crowd.frame();
        benchmark::ClobberMemory();
    }
    bench::reportNsPerJoint(state, numActors);
}

/** The console output, then per N the ratio of osgActor's time to ozz's, with every key frame and decimated
  * (below 1: osgActor faster). With --benchmark_repetitions, the medians. */
class RatioReporter : public benchmark::ConsoleReporter
{
public:
    void ReportRuns(const std::vector<Run>& runs) override
    {
        ConsoleReporter::ReportRuns(runs);
        for (const Run& run : runs)
        {
            // Single runs, or of repeated ones the median (reported after the repetitions, so it is the one kept).
            const bool aggregate = run.run_type == Run::RT_Aggregate;
            if ((aggregate && run.aggregate_name != "median") || run.error_occurred) continue;
            const auto counter = run.counters.find("ns_per_joint");
            if (counter == run.counters.end()) continue;
            _nsPerJoint[run.run_name.function_name][std::stol(run.run_name.args)] = counter->second.value * 1e9; // s
        }
    }
    void printRatios()
    {
        for (const auto& [n, osgActor] : _nsPerJoint["pose/osgActor"])
        {
            std::printf("pose alone  N = %4ld  osgActor %6.1f ns/joint", n, osgActor);
            for (const char* ozz : {"pose/ozz", "pose/ozz_optimized"})
                if (_nsPerJoint[ozz].count(n) != 0)
                    std::printf("  %s %6.1f (osgActor/ozz %.2f)", ozz + 5, _nsPerJoint[ozz][n],
                                osgActor / _nsPerJoint[ozz][n]);
            std::printf("\n");
        }
    }

private:
    std::map<std::string, std::map<long, double>> _nsPerJoint; // benchmark, N
};

} // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    for (const long n : {1L, 10L, 100L, 1000L})
    {
        benchmark::RegisterBenchmark("pose/ozz", BM_PoseAlone_ozz, false)->Arg(n);
        benchmark::RegisterBenchmark("pose/ozz_optimized", BM_PoseAlone_ozz, true)->Arg(n);
        benchmark::RegisterBenchmark("pose/osgActor", BM_PoseAlone_osgActor)->Arg(n);
    }
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    reporter.printRatios();
    benchmark::Shutdown();
    return 0;
}
