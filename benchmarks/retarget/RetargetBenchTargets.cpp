#include "RetargetBenchTargets.h"

#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>
#include <osgActor/io/ActorReader>
#include <osgActor/mocap/BvhReader>

#include <fstream>
#include <stdexcept>

using namespace osgActor;

namespace bench {

namespace {

ActorDefinitionPtr humanoid()
{
    std::ifstream in(std::string(OSGACTOR_BENCH_DATA_DIR) + "/humanoid.actor");
    return readActor(in, "humanoid.actor").definition;
}

/** Cesium Man (data/models/CesiumMan, glTF), standing Z up in metres. */
ActorDefinitionPtr cesiumMan()
{
    const RiggedModelRead read =
        readRiggedModelFile(std::string(OSGACTOR_BENCH_DATA_DIR) + "/models/CesiumMan/CesiumMan.gltf");
    if (!read) throw std::runtime_error(read.error);
    RiggedActorOptions options;
    options.rootScale = RootScale::InLengths;
    options.zUp = true;
    return buildRiggedActor(read.model, options).definition;
}

} // namespace

MocapImport readBvh(const std::string& path, double scale, bool endSites)
{
    BvhImportOptions options;
    options.scale = scale;
    options.endSitesAsJoints = endSites;
    return readBvhFile(path, options);
}

const MocapImport& walk()
{
    static const MocapImport imported = readBvh(std::string(OSGACTOR_BENCH_MOCAP_DIR) + "/bvh/12_03.bvh", 1.0, false);
    return imported;
}

ActorDefinitionPtr target(int which)
{
    static const ActorDefinitionPtr targets[kNumTargets] = {
        walk().definition, humanoid(),
        readBvh("/usr/share/assimp/models/BVH/Boxing_Toes.bvh", 0.01, false).definition, cesiumMan()};
    return targets[which];
}

const char* const kTargetNames[kNumTargets] = {"same_skeleton", "humanoid", "boxing_toes", "cesium_man"};

RetargetRigPtr rigOnto(const MocapImport& source, const ActorDefinitionPtr& onto)
{
    RetargetSkeleton from, to;
    from.definition = source.definition;
    to.definition = onto;
    const RetargetRigBuildResult built = buildRetargetRig(from, to);
    if (!built) throw std::runtime_error(built.error);
    return built.rig;
}

RetargetJobOnto::RetargetJobOnto(int which) : clip(walk().clip.get()), rig(rigOnto(walk(), target(which)))
{
    workspace.resize(*rig);
    dofs = rig->getTargetRestDofs();
    job.rig = rig.get();
    job.targetDofs = dofs;
    job.workspace = &workspace;
}

} // namespace bench
