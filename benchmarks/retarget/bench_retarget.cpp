// Retargeting time per frame (issue 27), in the same run as a peer: the source skeleton's own forward kinematics of
// the same frame (ActorPose), so the ratio holds on a busy machine.
// - BM_SourceForwardKinematics: CMU's 12_03.bvh (31 joints, End Sites left out), one frame of its clip posed.
// - BM_RetargetJob/<target>: one frame of the same clip retargeted (RetargetJob) onto the same skeleton, the project's
//   H-Anim humanoid (data/humanoid.actor), Boxing_Toes.bvh's skeleton (assimp-testmodels, in metres) and the glTF
//   character Cesium Man (data/models/CesiumMan, its joints mapped by the topology guess).
// - BM_RetargetJobWithIk/<target>: the same and the IK pass (RetargetIkJob: both legs and both arms solved, feet held
//   at their plants during contacts), the goals worked out beforehand as retargetClip() does.
// - BM_RetargetClip/<source>/<target>: retargetClip() with the IK pass, whole clips, per frame (its contact search,
//   sampling and the clip built included), with the measures of issue 27 as counters: the largest slip of a planted
//   foot (cm on a 1.75 m body) and the largest distance of an ankle or wrist from where the source puts it (% of the
//   body's height).
#include <osgActor/core/ActorPose>
#include <osgActor/core/retarget/RetargetClip>
#include <osgActor/core/retarget/RetargetIkJob>
#include <osgActor/core/retarget/RetargetJob>
#include <osgActor/core/retarget/RetargetLimbs>
#include <osgActor/core/retarget/RetargetMeasures>
#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/AsfReader>

#include "RetargetBenchTargets.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

using namespace osgActor;
using bench::kTargetNames;
using bench::readBvh;
using bench::rigOnto;
using bench::target;
using bench::walk;

namespace {

void perFrame(benchmark::State& state, double frames)
{
    state.counters["per_frame"] =
        benchmark::Counter(frames, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_SourceForwardKinematics(benchmark::State& state)
{
    const MocapImport& source = walk();
    ActorPose pose(source.definition);
    unsigned frame = 0;
    for (auto _ : state)
    {
        pose.setDofs(source.clip->getFrame(frame), source.clip->getNumChannels());
        pose.updateMatrices();
        benchmark::DoNotOptimize(pose.getModelMatrix(pose.getNumJoints() - 1));
        frame = frame + 1 < source.clip->getNumFrames() ? frame + 1 : 0;
    }
    state.counters["joints"] = source.definition->getNumJoints();
}

void BM_RetargetJob(benchmark::State& state)
{
    const MocapImport& source = walk();
    bench::RetargetJobOnto onto(static_cast<int>(state.range(0)));
    RetargetJob& job = onto.job;
    unsigned frame = 0;
    for (auto _ : state)
    {
        job.sourceDofs = Span<const double>(source.clip->getFrame(frame), source.clip->getNumChannels());
        job.run();
        benchmark::DoNotOptimize(onto.dofs.data());
        frame = frame + 1 < source.clip->getNumFrames() ? frame + 1 : 0;
    }
    state.SetLabel(kTargetNames[state.range(0)]);
    state.counters["source_joints"] = source.definition->getNumJoints();
    state.counters["target_joints"] = onto.rig->getTargetDefinition()->getNumJoints();
}

void BM_RetargetJobWithIk(benchmark::State& state)
{
    const MocapImport& source = walk();
    const RetargetRigPtr rig = rigOnto(source, target(static_cast<int>(state.range(0))));
    // The goals of every frame as retargetClip() makes them (its IK pass, with plants), read back from its clip.
    RetargetClipOptions options;
    options.ik = true;
    const RetargetClipResult reference = retargetClip(*rig, *source.clip, options);
    const RetargetLimbs limbs = buildRetargetLimbs(*rig);
    const std::size_t numLimbs = limbs.limbs.size();
    std::vector<IkGoal> allGoals(std::size_t(reference.numFrames) * numLimbs);
    {
        ActorPose pose(rig->getTargetDefinition());
        for (unsigned f = 0; f < reference.numFrames; ++f)
        {
            pose.setDofs(reference.clip->getFrame(f), reference.clip->getNumChannels());
            pose.updateMatrices();
            for (std::size_t i = 0; i < numLimbs; ++i)
                allGoals[f * numLimbs + i].position =
                    glm::dvec3(pose.getModelMatrix(limbs.limbs[i].chain->getEffectorJoint())[3]);
        }
    }
    RetargetWorkspace workspace;
    workspace.resize(*rig);
    std::vector<double> dofs = rig->getTargetRestDofs();
    std::vector<IkWorkspace> ikWorkspaces(numLimbs);
    for (std::size_t i = 0; i < numLimbs; ++i) ikWorkspaces[i].resize(*limbs.limbs[i].chain);
    RetargetJob job;
    job.rig = rig.get();
    job.targetDofs = dofs;
    job.workspace = &workspace;
    RetargetIkJob ik;
    ik.rig = rig.get();
    ik.limbs = &limbs;
    ik.targetDofs = dofs;
    ik.workspace = &workspace;
    ik.ikWorkspaces = ikWorkspaces;
    unsigned frame = 0;
    for (auto _ : state)
    {
        job.sourceDofs = Span<const double>(source.clip->getFrame(frame), source.clip->getNumChannels());
        job.run();
        ik.goals = Span<const IkGoal>(allGoals.data() + std::size_t(frame) * numLimbs, numLimbs);
        ik.run();
        benchmark::DoNotOptimize(dofs.data());
        frame = frame + 1 < source.clip->getNumFrames() ? frame + 1 : 0;
    }
    state.SetLabel(kTargetNames[state.range(0)]);
    state.counters["limbs"] = static_cast<double>(numLimbs);
}

/** 0: CMU 01_01.bvh (assimp-testmodels), 1: CMU 11_01.amc (data/mocap, metres). */
const MocapImport& clipSource(int which)
{
    static const MocapImport sources[2] = {
        readBvh("/usr/share/assimp/models/BVH/01_01.bvh", 1.0, true), [] {
            AsfImportOptions options;
            options.scale = 2.54 / 100.0 / 0.45;
            options.applyLimits = false;
            const AsfImport skeleton =
                readAsfFile(std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/asfamc/11.asf", options);
            return readAmcFile(std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/asfamc/11_01.amc", skeleton);
        }()};
    return sources[which];
}

void BM_RetargetClip(benchmark::State& state)
{
    const MocapImport& source = clipSource(static_cast<int>(state.range(0)));
    const RetargetRigPtr rig = rigOnto(source, target(1 + static_cast<int>(state.range(1))));
    RetargetClipOptions options;
    options.ik = state.range(2) != 0;
    RetargetClipResult result;
    for (auto _ : state)
    {
        result = retargetClip(*rig, *source.clip, options);
        benchmark::DoNotOptimize(result.clip.get());
    }
    perFrame(state, result.numFrames);
    if (!options.ik)
    {
        // The contacts of the IK pass, to measure how far the feet slide without it.
        RetargetClipOptions withIk = options;
        withIk.ik = true;
        result.feet = retargetClip(*rig, *source.clip, withIk).feet;
    }
    const RetargetMeasures measures = measureRetargetedClip(*rig, *source.clip, result);
    double largestEnd = 0.0;
    for (const RetargetMeasures::End& end : measures.ends) largestEnd = std::max(largestEnd, end.largestError);
    state.counters["slip_cm_at_1.75m"] = 100.0 * measures.largestSlip * 1.75 / measures.targetHeight;
    state.counters["end_error_pct_height"] = 100.0 * largestEnd / measures.targetHeight;
    state.counters["contacts"] = static_cast<double>(measures.contacts.size());
    state.SetLabel(std::string(state.range(0) == 0 ? "01_01.bvh" : "11_01.amc") + " onto " +
                   kTargetNames[1 + state.range(1)] + (options.ik ? ", IK" : ", no IK"));
}

} // namespace

BENCHMARK(BM_SourceForwardKinematics)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RetargetJob)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RetargetJobWithIk)->DenseRange(1, 3)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RetargetClip)->ArgsProduct({{0, 1}, {0, 1, 2}, {0, 1}})->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
