#include <osgActor/ActorPartsText>
#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <sstream>

namespace osgActor {

namespace {

std::vector<std::string> linesOf(const std::string& text)
{
    std::vector<std::string> lines;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

std::string textOf(const std::vector<std::string>& lines)
{
    std::string text;
    for (const std::string& line : lines) text += line + "\n";
    return text;
}

/** The sections of a document's actor block (its clips, trajectories, players, IK chains), without the block. */
std::vector<std::string> sectionLines(const ActorDocument& document)
{
    std::ostringstream text;
    {
        SyntaxWriter writer(text);
        writeActorBlock(writer, document);
    }
    return linesOf(text.str());
}

/** readActor() over lines, its error, if any, in error. */
ActorReadResult readWholeText(const std::vector<std::string>& lines, const std::string& where, std::string& error)
{
    std::istringstream in(textOf(lines));
    ActorReadResult read = readActor(in, where);
    if (!read) error = read.error;
    return read;
}

/** readActorMotion() over lines, its error, if any, in error. */
ActorReadResult readMotionText(const std::vector<std::string>& lines, const std::string& where,
                               const ActorDefinitionPtr& definition, const std::vector<ClipPtr>& knownClips,
                               std::string& error)
{
    std::istringstream in(textOf(lines));
    ActorReadResult read = readActorMotion(in, where, definition, knownClips);
    if (!read) error = read.error;
    return read;
}

bool holdsMotion(const ActorDocument& document)
{
    return !document.clips.empty() || !document.trajectories.empty() || !document.players.empty() ||
           !document.ikChains.empty();
}

/** Whether a document sets how the views treat its actor ("cull", "update_policy"), which only an actor holds. */
bool holdsCullOrUpdatePolicy(const ActorDocument& document)
{
    return document.cullNodeByNode || !document.updatePolicy.isDefault();
}

/** The library's clips, in name order. */
std::vector<ClipPtr> clipsOf(const ClipLibrary* library)
{
    std::vector<ClipPtr> clips;
    if (library)
        for (const std::string& name : library->getClipNames()) clips.push_back(library->getClip(name));
    return clips;
}

} // namespace

std::vector<std::string> writeDefinitionLines(const ActorDefinition& definition)
{
    std::ostringstream text;
    writeActor(text, makeDocument(definition));
    return linesOf(text.str());
}

ActorDefinitionPtr readDefinitionLines(const std::vector<std::string>& lines, const std::string& where,
                                       std::string& error)
{
    const ActorReadResult read = readWholeText(lines, where, error);
    if (!read) return nullptr;
    // What the text holds besides the joints would be lost: refuse it rather than read part of it.
    if (holdsMotion(read.document) || holdsCullOrUpdatePolicy(read.document) || !read.document.sections.empty())
    {
        error = where + ": a definition holds joints only, and this one has clips, trajectories, players, IK chains, "
                        "a cull mode, an update policy or other sections";
        return nullptr;
    }
    return read.definition;
}

std::vector<std::string> writeClipLines(const ClipLibrary& library)
{
    ActorDocument document;
    for (const ClipPtr& clip : clipsOf(&library))
    {
        ClipDocument written;
        written.clip = clip;
        document.clips.push_back(written);
    }
    return sectionLines(document);
}

ClipLibraryPtr readClipLines(const std::vector<std::string>& lines, const ActorDefinitionPtr& definition,
                             const std::string& where, std::string& error)
{
    const ActorReadResult read = readMotionText(lines, where, definition, {}, error);
    if (!read) return nullptr;
    ClipLibraryPtr library = std::make_shared<ClipLibrary>();
    for (const ClipDocument& clip : read.document.clips)
    {
        if (!clip.clip)
        {
            error = where + ":" + std::to_string(clip.line) + ": clip '" + clip.name() +
                    "' reads a motion file, which a clip library cannot";
            return nullptr;
        }
        library->addClip(clip.clip);
    }
    if (!read.document.trajectories.empty() || !read.document.players.empty() || !read.document.ikChains.empty() ||
        holdsCullOrUpdatePolicy(read.document))
    {
        error = where + ": a clip library holds clips only, and this one has trajectories, players, IK chains, a cull "
                        "mode or an update policy";
        return nullptr;
    }
    return library;
}

std::vector<std::string> writeMotionLines(const ActorNode& actor)
{
    ActorDocument document;
    document.name = actor.getName();
    // The library's clips are written with the library: they are here only so that addPlayers() adds the clips
    // its players play that the library lacks, and go again before writing.
    addClips(actor, document);
    const std::size_t libraryClips = document.clips.size();
    addTrajectories(actor, document);
    addPlayers(actor, document);
    addIkChains(actor, document);
    addCullAndUpdatePolicy(actor, document);
    document.clips.erase(document.clips.begin(), document.clips.begin() + static_cast<std::ptrdiff_t>(libraryClips));
    return sectionLines(document);
}

bool readMotionLines(ActorNode& actor, const std::vector<std::string>& lines, const std::string& where,
                     std::string& error)
{
    if (lines.empty()) return true;
    const std::vector<ClipPtr> known = clipsOf(actor.getClipLibrary().get());
    const ActorReadResult read = readMotionText(lines, where, actor.getDefinition(), known, error);
    if (!read) return false;
    if (read.document.clips.size() > known.size()) applyClips(actor, read.document);
    applyTrajectories(actor, read.document);
    applyPlayers(actor, read.document);
    applyCullAndUpdatePolicy(actor, read.document);
    for (const IkChainPtr& chain : read.ikChains) actor.addIkChain(chain);
    return true;
}

bool readWholeActorLines(ActorNode& actor, const std::vector<std::string>& lines, const std::string& where,
                         std::string& error)
{
    const ActorReadResult read = readWholeText(lines, where, error);
    if (!read) return false;
    if (!actor.setDefinition(read.definition, ActorNode::BIND_EXISTING_SKELETON_NODES))
    {
        error = "the skeleton nodes of actor '" + actor.getName() + "' do not match its definition";
        return false;
    }
    applyDefinitionDocument(actor, read.document, read.ikChains);
    return true;
}

} // namespace osgActor
