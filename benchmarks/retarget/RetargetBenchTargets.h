// The retargeting benchmarks' source and targets (issue 27), shared by the timing benchmark (bench_retarget.cpp) and
// the instruction counts under callgrind (retarget_counts.cpp).
#ifndef OSGACTOR_BENCH_RETARGET_BENCHTARGETS_H
#define OSGACTOR_BENCH_RETARGET_BENCHTARGETS_H 1

#include <osgActor/core/retarget/RetargetJob>
#include <osgActor/core/retarget/RetargetRig>
#include <osgActor/mocap/MocapImport>

#include <string>
#include <vector>

namespace bench {

/** A BVH file read with its positions scaled by scale (model units per file unit), End Sites as joints or not. */
osgActor::MocapImport readBvh(const std::string& path, double scale, bool endSites);
/** CMU's 12_03.bvh (data/mocap, 31 joints, End Sites left out): the source of the per-frame benchmarks. */
const osgActor::MocapImport& walk();
/** 0: the source's own skeleton, 1: the project's H-Anim humanoid (data/humanoid.actor), 2: Boxing_Toes.bvh's
  * skeleton (assimp-testmodels, in metres), 3: the glTF character Cesium Man (data/models/CesiumMan, Z up, metres). */
osgActor::ActorDefinitionPtr target(int which);
constexpr int kNumTargets = 4;
extern const char* const kTargetNames[kNumTargets];
/** The rig from source's skeleton onto onto, its joints mapped automatically; throws if it cannot be built. */
osgActor::RetargetRigPtr rigOnto(const osgActor::MocapImport& source, const osgActor::ActorDefinitionPtr& onto);

/** A RetargetJob from walk() onto target(which): its rig, workspace (sized) and target DOFs (at rest to begin with).
  * Not copied or moved: the job points at the others. */
struct RetargetJobOnto
{
    explicit RetargetJobOnto(int which);
    RetargetJobOnto(const RetargetJobOnto&) = delete;
    RetargetJobOnto& operator=(const RetargetJobOnto&) = delete;

    /** Retargets frame f of walk()'s clip into dofs; false if the job refused it. Inline, so a loop of it counts the
      * job and the loop only. */
    bool runFrame(unsigned f)
    {
        job.sourceDofs = osgActor::Span<const double>(clip->getFrame(f), clip->getNumChannels());
        return job.run();
    }

    /** walk()'s clip. */
    const osgActor::Clip* clip;
    osgActor::RetargetRigPtr rig;
    osgActor::RetargetWorkspace workspace;
    std::vector<double> dofs;
    osgActor::RetargetJob job;
};

} // namespace bench

#endif
