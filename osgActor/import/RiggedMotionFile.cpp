#include <osgActor/import/RiggedMotionFile>

#include <osgActor/import/RiggedActorBuilder>
#include <osgActor/import/RiggedModelFile>

#include <algorithm>
#include <memory>

namespace osgActor {

MocapImport readRiggedMotionFile(const std::string& path, const MotionFileOptions& options)
{
    MocapImport motion;
    if (options.scale != 1.0)
    {
        motion.error = path + ": a rigged model's motion is read in its own units (scale 1), not scaled";
        return motion;
    }
    const RiggedModelRead read = readRiggedModelFile(path);
    if (!read)
    {
        motion.error = read.error;
        return motion;
    }
    const std::vector<RiggedAnimation>& animations = read.model->animations;
    const auto chosen = std::find_if(animations.begin(), animations.end(), [&](const RiggedAnimation& animation) {
        return options.animation.empty() || animation.name == options.animation;
    });
    if (chosen == animations.end())
    {
        std::string names;
        for (const RiggedAnimation& animation : animations) names += (names.empty() ? "'" : ", '") + animation.name + "'";
        motion.error = animations.empty() ? path + ": the model has no animation"
                                          : path + ": no animation '" + options.animation + "' (the file has " + names +
                                                ")";
        return motion;
    }
    // The skeleton and that animation alone, named as the clip is to be: a copy of the model that keeps only it.
    const std::shared_ptr<RiggedModel> model = std::make_shared<RiggedModel>(*read.model);
    model->animations = {*chosen};
    if (!options.name.empty()) model->animations.front().name = options.name;
    RiggedActorOptions mapping;
    mapping.rootScale = RootScale::InLengths;
    mapping.zUp = options.fileUpAxis == UpAxis::Y;
    const RiggedActor actor = buildRiggedActor(model, mapping);
    if (!actor)
    {
        motion.error = actor.error;
        return motion;
    }
    motion.definition = actor.definition;
    motion.clip = actor.clips.front();
    motion.warnings = read.warnings;
    motion.warnings.insert(motion.warnings.end(), actor.warnings.begin(), actor.warnings.end());
    return motion;
}

MocapImport readAnyMotionFile(const std::string& path, const MotionFileOptions& options)
{
    return isRiggedModelFile(path) ? readRiggedMotionFile(path, options) : readMotionFile(path, options);
}

} // namespace osgActor
