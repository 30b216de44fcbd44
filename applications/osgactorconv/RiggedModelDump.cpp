#include "RiggedModelDump"

#include <osgActor/core/ActorPose>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinningJob>
#include <osgActor/import/ChannelSampling>
#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>
#include <osgActor/import/UniformClip>
#include <osgActor/mocap/PositionsCsv>

#include <cstdio>
#include <fstream>

using namespace osgActor;

namespace {

/** Writes frame,mesh,vertex,x,y,z for every skinned primitive (mesh: its index in actor.skins, the file's
  * meshes[] then primitives[] order) at every frame of the sampled clip: positions skinned on the CPU by the core's
  * jobs, in the actor's model space (the file's scene space here). */
bool writeSkinnedCsv(std::ostream& out, const RiggedActor& actor, const Clip& frames, std::string& error)
{
    std::vector<SkinBinding> bindings;
    for (const SkinnedPrimitive& skinned : actor.skins)
    {
        bindings.push_back(bindSkinToDefinition(*skinned.skin, *actor.definition));
        if (!bindings.back())
        {
            error = bindings.back().error;
            return false;
        }
    }
    std::vector<int> dofOfChannel(frames.getNumChannels());
    for (unsigned c = 0; c < frames.getNumChannels(); ++c)
        dofOfChannel[c] = actor.definition->findDof(frames.getChannel(c).target);
    ActorPose pose(actor.definition);
    out << "frame,mesh,vertex,x,y,z\n";
    char row[160];
    for (unsigned f = 0; f < frames.getNumFrames(); ++f)
    {
        const double* values = frames.getFrame(f);
        for (unsigned c = 0; c < frames.getNumChannels(); ++c) pose.setDof(unsigned(dofOfChannel[c]), values[c]);
        pose.updateMatrices();
        for (std::size_t s = 0; s < actor.skins.size(); ++s)
        {
            const Skin& skin = *actor.skins[s].skin;
            std::vector<glm::mat4> matrices(skin.getNumJoints());
            SkinningMatricesJob skinningMatrices;
            skinningMatrices.modelMatrices = modelMatricesOf(pose);
            skinningMatrices.definitionJoints = bindings[s].definitionJoints;
            skinningMatrices.inverseBindMatrices = skin.getInverseBindMatrices();
            skinningMatrices.matrices = matrices;
            std::vector<glm::vec3> positions(skin.getNumVertices());
            SkinningJob skinning;
            skinning.vertices = skin.getVertices();
            skinning.matrices = matrices;
            skinning.positions = positions;
            if (!skinningMatrices.run() || !skinning.run())
            {
                error = "the skin of " + actor.model->meshes[actor.skins[s].mesh].primitives[actor.skins[s].primitive].place +
                        " could not be skinned";
                return false;
            }
            for (std::size_t v = 0; v < positions.size(); ++v)
            {
                const glm::vec3& p = positions[v];
                std::snprintf(row, sizeof(row), "%u,%zu,%zu,%.9g,%.9g,%.9g\n", f, s, v, p.x + 0.0, p.y + 0.0, p.z + 0.0);
                out << row;
            }
        }
    }
    if (!out) error = "the output could not be written";
    return bool(out);
}

} // namespace

int runRiggedModelDump(const RiggedModelDumpRequest& request, std::ostream& err)
{
    const RiggedModelRead read = readRiggedModelFile(request.input);
    if (!read)
    {
        err << "osgactorconv: " << read.error << "\n";
        return 1;
    }
    RiggedActorOptions options;
    options.rootScale = RootScale::InLengths; // the file's own units: model space is the scene's root space
    const RiggedActor actor = buildRiggedActor(read.model, options);
    if (!actor)
    {
        err << "osgactorconv: " << actor.error << "\n";
        return 1;
    }
    for (const std::string& warning : read.warnings) err << "osgactorconv: warning: " << warning << "\n";
    for (const std::string& warning : actor.warnings) err << "osgactorconv: warning: " << warning << "\n";

    // The clip and its animation (same name): the sampled times run over the animation's keys.
    const RiggedAnimation* animation = nullptr;
    for (const RiggedAnimation& each : read.model->animations)
        if (request.clip.empty() ? true : each.name == request.clip)
        {
            animation = &each;
            break;
        }
    ClipPtr clip;
    for (const ClipPtr& each : actor.clips)
        if (animation && each->getName() == animation->name) clip = each;
    if (!clip)
    {
        err << "osgactorconv: " << request.input << ": "
            << (request.clip.empty() ? std::string("the file holds no animation to dump")
                                     : "no animation named '" + request.clip + "' moves a joint")
            << "\n";
        return 1;
    }
    double first, last;
    animationTimeRange(*animation, first, last);
    const ClipBuildResult frames = sampleClipUniformly(*clip, first, last, request.fps);
    if (!frames)
    {
        err << "osgactorconv: " << frames.error << "\n";
        return 1;
    }
    std::string error;
    if (request.positions &&
        !writePositionsCsv(*request.positions, actor.definition, *frames.clip, 0, frames.clip->getNumFrames(), error))
    {
        err << "osgactorconv: " << error << "\n";
        return 1;
    }
    if (!request.skinnedPath.empty())
    {
        std::ofstream skinned(request.skinnedPath, std::ios::binary);
        if (!skinned)
        {
            err << "osgactorconv: " << request.skinnedPath << ": cannot write the file\n";
            return 1;
        }
        if (!writeSkinnedCsv(skinned, actor, *frames.clip, error))
        {
            err << "osgactorconv: " << request.skinnedPath << ": " << error << "\n";
            return 1;
        }
    }
    return 0;
}
