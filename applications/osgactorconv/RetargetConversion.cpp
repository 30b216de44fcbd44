#include "RetargetConversion.h"

#include <osgActor/core/retarget/RetargetMeasures>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>
#include <osgActor/io/JointMapSection>

#include <algorithm>
#include <fstream>
#include <iostream>

using namespace osgActor;

namespace {

int fail(const std::string& message)
{
    std::cerr << "osgactorconv: " << message << "\n";
    return 1;
}

} // namespace

int retargetIntoActorFile(const RetargetConversion& conversion, const MocapImport& motion)
{
    if (!motion.clip) return fail("the input holds no motion to retarget");
    std::ifstream in(conversion.targetFile, std::ios::binary);
    if (!in) return fail(conversion.targetFile + ": cannot read the file");
    ActorReadResult target = readActor(in, conversion.targetFile);
    if (!target) return fail(target.error);

    ActorJointMaps maps;
    std::string error;
    if (!readActorJointMaps(target.document.sections, conversion.targetFile, maps, error)) return fail(error);
    RetargetSkeleton from, onto;
    from.definition = motion.definition;
    onto.definition = target.definition;
    if (maps.hasOwn) onto.map = maps.own;
    if (!conversion.mapFile.empty() && !readJointMapFile(conversion.mapFile, from.map, error)) return fail(error);
    const RetargetRigBuildResult rig = buildRetargetRig(from, onto);
    if (!rig) return fail(rig.error);
    for (const std::string& note : rig.rig->getNotes()) std::cerr << "osgactorconv: " << note << "\n";

    RetargetClipOptions options;
    options.ik = conversion.ik;
    const RetargetClipResult result = retargetClip(*rig.rig, *motion.clip, options);
    if (!result) return fail(result.error);
    const RetargetMeasures measures = measureRetargetedClip(*rig.rig, *motion.clip, result);
    double largestEnd = 0.0;
    for (const RetargetMeasures::End& end : measures.ends) largestEnd = std::max(largestEnd, end.largestError);
    std::cerr << "osgactorconv: clip '" << result.clip->getName() << "' retargeted onto '" << target.document.name
              << "': " << result.numFrames << " frames, scale " << rig.rig->getScale() << ", "
              << measures.contacts.size() << " foot contacts, largest slip " << measures.largestSlip
              << " and end error " << largestEnd
              << " (model units; the body is " << measures.targetHeight << " tall)\n";

    std::vector<ClipDocument>& clips = target.document.clips;
    clips.erase(std::remove_if(clips.begin(), clips.end(),
                               [&](const ClipDocument& clip) { return clip.name() == result.clip->getName(); }),
                clips.end());
    ClipDocument clip;
    clip.clip = result.clip;
    clip.play = target.document.players.empty() &&
                std::none_of(clips.begin(), clips.end(), [](const ClipDocument& other) { return other.play; });
    clips.push_back(clip);

    const std::string& output = conversion.outputFile.empty() ? conversion.targetFile : conversion.outputFile;
    std::ofstream out(output, std::ios::binary);
    if (!out) return fail(output + ": cannot write the file");
    writeActor(out, target.document);
    if (!out) return fail(output + ": cannot write the file");
    return 0;
}
