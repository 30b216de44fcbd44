#include <osgActor/ActorGeometry>
#include <osgActor/ActorSceneIO>
#include <osgActor/core/ClipPlayer>
#include <osgActor/GlmOsg>
#include <osgActor/RiggedModelActor>
#include <osgActor/io/ActorSyntax>
#include <osgActor/io/ClipRetarget>
#include <osgActor/import/RiggedMotionFile>
#include <osgActor/mocap/TrajectoryCsv>

#include <osg/Notify>
#include <osg/ValueObject>
#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>

#include <algorithm>
#include <sstream>

namespace osgActor {

const char* const kSectionsUserValue = "osgActorSections";

namespace {

/** Options whose data file path starts with the folder of the file being read, so that models are found next
  * to it first (as OSG's own plugins do). */
osg::ref_ptr<osgDB::Options> optionsNextTo(const std::string& fileName, const osgDB::Options* options)
{
    osg::ref_ptr<osgDB::Options> local =
        options ? static_cast<osgDB::Options*>(options->clone(osg::CopyOp::SHALLOW_COPY)) : new osgDB::Options;
    const std::string folder = osgDB::getFilePath(fileName);
    if (!folder.empty()) local->getDatabasePathList().push_front(folder);
    return local;
}

std::string where(const std::string& fileName, int line) { return fileName + ":" + std::to_string(line) + ": "; }

/** Finds a file a .actor file names (next to it first: optionsNextTo), or sets error to prefix + "cannot find the
  * <what> '<file>'" and returns empty. */
std::string findNamedFile(const std::string& file, const char* what, const osgDB::Options* options,
                          const std::string& prefix, std::string& error)
{
    const std::string path = osgDB::findDataFile(file, options);
    if (path.empty()) error = prefix + "cannot find the " + what + " '" + file + "'";
    return path;
}

/** Loads one model of the document; null and an error when it cannot. */
osg::ref_ptr<osg::Node> loadModel(const GeometryDescription& model, const std::string& fileName,
                                  const osgDB::Options* options, std::string& error)
{
    const std::string path = findNamedFile(model.file, "model file", options, where(fileName, model.line), error);
    if (path.empty()) return nullptr;
    osg::ref_ptr<osg::Node> node = osgDB::readRefNodeFile(path, options);
    if (!node) error = where(fileName, model.line) + "cannot read the model file '" + path + "'";
    return node;
}

/** Puts the skins of the document's rigged model files below the actor, in its model space; false and an error
  * (naming fileName and the skin statement's line) when a file cannot be found or read or a skin does not fit. */
bool attachSkins(ActorNode& actor, const ActorDocument& document, const std::string& fileName,
                 const osgDB::Options* options, std::string& error)
{
    for (const SkinFileDocument& skin : document.skinFiles)
    {
        const std::string path = findNamedFile(skin.file, "skin file", options, where(fileName, skin.line), error);
        if (path.empty()) return false;
        std::string why;
        const osg::ref_ptr<osg::Geode> skins = readRiggedModelSkins(path, skin.file, *actor.getDefinition(), why);
        if (!skins)
        {
            error = where(fileName, skin.line) + why;
            return false;
        }
        actor.addChild(skins.get());
    }
    return true;
}

/** Adds the rigged model files whose skins hang below the actor (readRiggedModelSkins(), readRiggedModelActor()) to
  * a document; skinned meshes of another origin cannot be described by the format: left out with a warning. */
void addSkinFiles(const ActorNode& actor, ActorDocument& document)
{
    for (unsigned c = 0; c < actor.getNumChildren(); ++c)
    {
        const osg::Node* child = actor.getChild(c);
        if (dynamic_cast<const SkeletonNode*>(child)) continue;
        const std::string file = getSkinsNodeFile(*child);
        if (!file.empty())
        {
            if (std::none_of(document.skinFiles.begin(), document.skinFiles.end(),
                             [&](const SkinFileDocument& skin) { return skin.file == file; }))
                document.skinFiles.push_back(SkinFileDocument{file, 0});
            continue;
        }
        if (!findSkinnedMeshes(*const_cast<osg::Node*>(child)).empty())
            OSG_WARN << "osgActor: writing actor '" << document.name << "': its " << child->className() << " '"
                     << child->getName() << "' holds skinned meshes that no rigged model file describes; they are "
                        "left out (write .osgt to keep them)" << std::endl;
    }
}

/** The instance state a joint of the document carries: its current DOF values and hide flag. */
void applyJointState(ActorNode& actor, unsigned joint, const JointDocument& document)
{
    const ActorDefinition& definition = *actor.getDefinition();
    for (unsigned d = 0; d < kNumDofTypes; ++d)
    {
        if (!document.values[d]) continue; // most joints carry no value: no look-up in the definition for them
        const int dof = definition.getDofIndex(joint, static_cast<Dof>(d));
        if (dof >= 0) actor.setDof(static_cast<unsigned>(dof), *document.values[d]);
    }
    // A new node is shown: touch only those the document hides (a pass over every node of a large actor is paid in
    // cache misses).
    if (document.hidden) actor.getSkeletonNode(joint)->setHidden(true);
}

/** Hangs a joint's shapes and models below its skeleton node; false and an error when a model cannot be loaded. */
bool attachGeometry(SkeletonNode& node, const JointDocument& joint, const std::string& fileName,
                    const osgDB::Options* options, std::string& error)
{
    for (const GeometryDescription& geometry : joint.geometry)
    {
        if (geometry.kind != GeometryKind::Model)
        {
            node.addChild(createShapeNode(geometry).get());
            continue;
        }
        const osg::ref_ptr<osg::Node> model = loadModel(geometry, fileName, options, error);
        if (!model) return false;
        node.addChild(createModelNode(geometry, model.get()).get());
    }
    return true;
}

/** Why a clip read from a motion-capture file would not move the actor as it moved the file's own skeleton, or
  * empty when it would: each channel must name a DOF of the actor, on a joint that turns in the same Euler order
  * (a rotation) or slides in the same translation mode (a translation) as in the file, so that every value means the
  * same motion. Bone lengths may differ. */
std::string mismatchWithActor(const MocapImport& imported, const ActorDefinition& actor)
{
    const ActorDefinition& file = *imported.definition;
    for (unsigned c = 0; c < imported.clip->getNumChannels(); ++c)
    {
        const std::string& target = imported.clip->getChannel(c).target;
        const int dof = actor.findDof(target);
        const int fileDof = file.findDof(target);
        if (dof < 0 || fileDof < 0) return "its channel '" + target + "' names no DOF of the actor";
        const unsigned joint = actor.getDofJoint(static_cast<unsigned>(dof));
        const unsigned fileJoint = file.getDofJoint(static_cast<unsigned>(fileDof));
        const std::string& name = actor.getJointName(joint);
        if (isRotation(actor.getDofType(static_cast<unsigned>(dof))))
        {
            if (actor.getEulerOrder(joint) != file.getEulerOrder(fileJoint))
                return "joint '" + name + "' turns in " + eulerOrderName(file.getEulerOrder(fileJoint)) +
                       " order in the file and in " + eulerOrderName(actor.getEulerOrder(joint)) + " order here";
        }
        else if (actor.getTranslationMode(joint) != file.getTranslationMode(fileJoint))
        {
            return "joint '" + name + "' translates " +
                   (file.getTranslationMode(fileJoint) == TranslationMode::BeforeRotation ? "before" : "after") +
                   " its rotation in the file and not here";
        }
    }
    return std::string();
}

/** Reads the clips of the document whose motion is in a file (ClipDocument::file), found like model files (next
  * to the .actor file first); false and an error naming the .actor file and the clip's line when one cannot be read
  * or would not drive the actor. */
bool readClipFiles(std::vector<ClipDocument>& clips, const ActorDefinitionPtr& actor,
                   const std::vector<SyntaxStatement>& sections, const std::string& fileName,
                   const osgDB::Options* options, std::string& error)
{
    for (ClipDocument& clip : clips)
    {
        if (clip.file.empty() || clip.clip) continue;
        const std::string prefix = where(fileName, clip.line) + "clip '" + clip.name() + "': ";
        const std::string path = findNamedFile(clip.file, "motion file", options, prefix, error);
        if (path.empty()) return false;
        MotionFileOptions motionOptions = clip.fileOptions;
        if (!motionOptions.skeletonFile.empty())
        {
            motionOptions.skeletonFile =
                findNamedFile(clip.fileOptions.skeletonFile, "skeleton file", options, prefix, error);
            if (motionOptions.skeletonFile.empty()) return false;
        }
        const MocapImport imported = readAnyMotionFile(path, motionOptions);
        if (!imported)
        {
            error = prefix + imported.error;
            return false;
        }
        for (const std::string& warning : imported.warnings) OSG_WARN << "osgActor: " << warning << std::endl;
        if (!imported.clip)
        {
            error = prefix + "'" + path + "' holds no motion";
            return false;
        }
        if (clip.retarget.enabled)
        {
            clip.clip = retargetClipForActor(imported, actor, clip.retarget, sections, fileName, error);
            if (!clip.clip) error = where(fileName, clip.retarget.line) + "clip '" + clip.name() + "': " + error;
            if (!clip.clip) return false;
            continue;
        }
        const std::string mismatch = mismatchWithActor(imported, *actor);
        if (!mismatch.empty())
        {
            error = prefix + "'" + path + "' does not fit the actor: " + mismatch;
            return false;
        }
        clip.clip = imported.clip;
    }
    return true;
}

/** Reads the trajectories of the document whose keys are in a CSV file (TrajectoryDocument::file), found like model
  * files; false and an error naming the .actor file and the trajectory's line when one cannot be found or read. */
bool readTrajectoryFiles(std::vector<TrajectoryDocument>& trajectories, const std::string& fileName,
                         const osgDB::Options* options, std::string& error)
{
    for (TrajectoryDocument& trajectory : trajectories)
    {
        if (trajectory.file.empty() || trajectory.trajectory) continue;
        const std::string prefix = where(fileName, trajectory.line) + "trajectory '" + trajectory.name() + "': ";
        const std::string path = findNamedFile(trajectory.file, "file", options, prefix, error);
        if (path.empty()) return false;
        const TrajectoryBuildResult read = readTrajectoryCsvFile(path);
        if (!read)
        {
            error = prefix + read.error;
            return false;
        }
        // Named as in the .actor file, whatever the CSV file is called.
        const TrajectoryBuildResult renamed = TrajectoryBuilder::build(trajectory.name(), read.trajectory->getKeys());
        trajectory.trajectory = renamed.trajectory;
    }
    return true;
}

std::string sectionsText(const std::vector<SyntaxStatement>& sections)
{
    std::ostringstream text;
    writeSyntax(text, sections);
    return text.str();
}

/** Puts what a player plays, a clip or a trajectory, into the document's list of them (the member of each document
  * that holds it), once; false, with a warning, when another of the same name is there already, which the file would
  * read back as that one. */
template <class Document, class Pointer>
bool takeForPlayer(std::vector<Document>& documents, Pointer Document::*member, const Pointer& played,
                   const char* kind, const std::string& playerName, const std::string& actorName)
{
    const auto named = std::find_if(documents.begin(), documents.end(),
                                    [&](const Document& d) { return d.name() == played->getName(); });
    if (named == documents.end())
    {
        Document kept;
        kept.*member = played;
        documents.push_back(std::move(kept));
        return true;
    }
    if ((*named).*member == played) return true;
    OSG_WARN << "osgActor: writing actor '" << actorName << "': player '" << playerName << "' plays another " << kind
             << " named like " << kind << " '" << played->getName() << "'; the player is left out" << std::endl;
    return false;
}

} // namespace

void applyClips(ActorNode& actor, const ActorDocument& document)
{
    if (document.clips.empty()) return;
    ClipLibraryPtr library = std::make_shared<ClipLibrary>();
    for (const ClipDocument& clip : document.clips)
    {
        if (!clip.clip)
        {
            // Only createActorNode() reads clip files; an embedded document (.osgt, .osg) carries its clips whole.
            OSG_WARN << "osgActor: clip '" << clip.name() << "' (file '" << clip.file
                     << "') was not read, so the actor lacks it" << std::endl;
            continue;
        }
        library->addClip(clip.clip);
        if (!clip.play) continue;
        // The "play" shorthand: a player named after the clip, everything else as a new player has it.
        auto player = std::make_shared<ClipPlayer>(clip.clip);
        player->setName(clip.clip->getName());
        player->setPlayMode(clip.playMode);
        player->play();
        actor.addController(player);
    }
    actor.setClipLibrary(library);
}

void applyPlayers(ActorNode& actor, const ActorDocument& document)
{
    const ClipLibrary* library = actor.getClipLibrary().get();
    for (const PlayerDocument& player : document.players)
    {
        if (player.playsTrajectory())
        {
            const auto found = std::find_if(document.trajectories.begin(), document.trajectories.end(),
                                            [&](const TrajectoryDocument& t) { return t.name() == player.trajectory; });
            // Only a trajectory whose file was not read (applyTrajectories() said so) lacks its keys here.
            if (found != document.trajectories.end() && found->trajectory)
                actor.addController(makeTrajectoryPlayer(player, found->trajectory));
            else
                OSG_WARN << "osgActor: player '" << player.name << "' plays trajectory '" << player.trajectory
                         << "', which the actor lacks; the player is left out" << std::endl;
            continue;
        }
        ClipPtr clip = library ? library->getClip(player.clip) : ClipPtr();
        if (!clip)
        {
            // Only a clip whose file was not read (applyClips() said so) is missing here; the reader checked names.
            OSG_WARN << "osgActor: player '" << player.name << "' plays clip '" << player.clip
                     << "', which the actor lacks; the player is left out" << std::endl;
            continue;
        }
        actor.addController(makeClipPlayer(player, std::move(clip), *actor.getDefinition()));
    }
}

void addClips(const ActorNode& actor, ActorDocument& document)
{
    const ClipLibrary* library = actor.getClipLibrary().get();
    if (!library) return;
    for (const std::string& name : library->getClipNames())
    {
        ClipDocument clip;
        clip.clip = library->getClip(name);
        document.clips.push_back(clip);
    }
}

void addPlayers(const ActorNode& actor, ActorDocument& document)
{
    for (const ControllerPtr& controller : actor.getControllers())
    {
        if (const auto* player = dynamic_cast<const TrajectoryPlayer*>(controller.get()))
        {
            if (player->getTrajectory() &&
                takeForPlayer(document.trajectories, &TrajectoryDocument::trajectory, player->getTrajectory(),
                              "trajectory", player->getName(), document.name))
                document.players.push_back(describeTrajectoryPlayer(*player));
            continue;
        }
        const auto* player = dynamic_cast<const ClipPlayer*>(controller.get());
        if (player && player->getClip() &&
            takeForPlayer(document.clips, &ClipDocument::clip, player->getClip(), "clip", player->getName(),
                          document.name))
            document.players.push_back(describeClipPlayer(*player, *actor.getDefinition()));
    }
}

void applyTrajectories(ActorNode& actor, const ActorDocument& document)
{
    for (const TrajectoryDocument& trajectory : document.trajectories)
    {
        if (!trajectory.trajectory)
        {
            // Only createActorNode() reads trajectory files; an embedded document carries its keys.
            OSG_WARN << "osgActor: trajectory '" << trajectory.name() << "' (file '" << trajectory.file
                     << "') was not read, so the actor lacks it" << std::endl;
            continue;
        }
        // A trajectory that a player section plays has that player (applyPlayers()) and none of its own.
        if (std::any_of(document.players.begin(), document.players.end(),
                        [&](const PlayerDocument& player) { return player.trajectory == trajectory.name(); }))
            continue;
        auto player = std::make_shared<TrajectoryPlayer>(trajectory.trajectory);
        player->setName(trajectory.trajectory->getName());
        player->setPlayMode(trajectory.playMode);
        player->setSpeed(trajectory.speed);
        if (!trajectory.play) player->pause();
        actor.addController(player);
    }
}

void addTrajectories(const ActorNode& actor, ActorDocument& document)
{
    for (const ControllerPtr& controller : actor.getControllers())
    {
        const TrajectoryPlayer* player = dynamic_cast<const TrajectoryPlayer*>(controller.get());
        if (player && player->getTrajectory())
            takeForPlayer(document.trajectories, &TrajectoryDocument::trajectory, player->getTrajectory(),
                          "trajectory", player->getName(), document.name);
    }
}

void addIkChains(const ActorNode& actor, ActorDocument& document)
{
    for (const IkChainPtr& chain : actor.getIkChains())
        document.ikChains.push_back(IkChainDocument{chain->getSpec(), 0});
}

void applyCullAndUpdatePolicy(ActorNode& actor, const ActorDocument& document)
{
    actor.setCullMode(document.cullNodeByNode ? ActorNode::CULL_NODE_BY_NODE : ActorNode::CULL_AS_ONE);
    ActorNode::UpdatePolicy policy;
    policy.onlyWhenSeen = document.updatePolicy.onlyWhenSeen;
    policy.maxDistance = document.updatePolicy.maxDistance;
    policy.halfRateBelowPixels = document.updatePolicy.halfRateBelowPixels;
    policy.quarterRateBelowPixels = document.updatePolicy.quarterRateBelowPixels;
    actor.setUpdatePolicy(policy);
}

void addCullAndUpdatePolicy(const ActorNode& actor, ActorDocument& document)
{
    document.cullNodeByNode = actor.getCullMode() == ActorNode::CULL_NODE_BY_NODE;
    const ActorNode::UpdatePolicy& policy = actor.getUpdatePolicy();
    document.updatePolicy.onlyWhenSeen = policy.onlyWhenSeen;
    document.updatePolicy.maxDistance = policy.maxDistance;
    document.updatePolicy.halfRateBelowPixels = policy.halfRateBelowPixels;
    document.updatePolicy.quarterRateBelowPixels = policy.quarterRateBelowPixels;
}

void applyDefinitionDocument(ActorNode& actor, const ActorDocument& document, const std::vector<IkChainPtr>& ikChains)
{
    applyCullAndUpdatePolicy(actor, document);
    applyClips(actor, document);
    applyTrajectories(actor, document);
    applyPlayers(actor, document);
    for (const IkChainPtr& chain : ikChains) actor.addIkChain(chain);
}

ActorNodeResult createActorNode(const ActorDocument& document, const ActorDefinitionPtr& definition,
                                const std::string& fileName, const osgDB::Options* options)
{
    ActorNodeResult result;
    if (!definition || definition->getNumJoints() != document.joints.size())
    {
        result.error = where(fileName, document.line) + "the definition does not belong to the document";
        return result;
    }
    osg::ref_ptr<ActorNode> actor = new ActorNode(definition);
    actor->setName(document.name);
    actor->setPreTranslation(toOsg(document.preTranslation));
    actor->setPreRotation(toOsg(document.preRotation));
    actor->setPostTranslation(toOsg(document.postTranslation));
    actor->setPostRotation(toOsg(document.postRotation));

    const osg::ref_ptr<osgDB::Options> local = optionsNextTo(fileName, options);
    for (std::size_t j = 0; j < document.joints.size(); ++j)
    {
        const JointDocument& joint = document.joints[j];
        // readActor() puts the joints in the definition's order: look the name up only where that is not so.
        const int index = definition->getJointName(static_cast<unsigned>(j)) == joint.spec.name
                              ? static_cast<int>(j)
                              : definition->findJoint(joint.spec.name);
        SkeletonNode* node = index < 0 ? nullptr : actor->getSkeletonNode(static_cast<unsigned>(index));
        if (!node)
        {
            result.error = where(fileName, joint.line) + "joint '" + joint.spec.name + "' is not in the definition";
            return result;
        }
        applyJointState(*actor, static_cast<unsigned>(index), joint);
        if (!attachGeometry(*node, joint, fileName, local.get(), result.error)) return result;
    }
    if (!attachSkins(*actor, document, fileName, local.get(), result.error)) return result;
    // The motion sections alone, with their files read (a copy of the whole document would copy every joint).
    ActorDocument motion;
    motion.clips = document.clips;
    motion.trajectories = document.trajectories;
    motion.players = document.players;
    if (!readClipFiles(motion.clips, definition, document.sections, fileName, local.get(), result.error))
        return result;
    if (!readTrajectoryFiles(motion.trajectories, fileName, local.get(), result.error)) return result;
    applyClips(*actor, motion);
    applyTrajectories(*actor, motion);
    applyPlayers(*actor, motion);
    applyCullAndUpdatePolicy(*actor, document);
    std::vector<IkChainPtr> chains;
    if (!buildIkChains(document, *definition, fileName, chains, result.error)) return result;
    for (IkChainPtr& chain : chains) actor->addIkChain(std::move(chain));
    if (!document.sections.empty()) actor->setUserValue(kSectionsUserValue, sectionsText(document.sections));
    // Pose the actor's scene graph now, before it may be blocked: a blocked actor would otherwise show and answer
    // with its default pose until unblocked. Its model matrices follow on the first query (updatePose()).
    actor->update(nullptr);
    // Set only when it differs from the new actor's: setting it visits every skeleton node.
    const ActorNode::BoundMode boundMode =
        document.boundsCoverRotations ? ActorNode::BOUND_COVERS_ROTATIONS : ActorNode::BOUND_FOLLOWS_POSE;
    if (actor->getBoundMode() != boundMode) actor->setBoundMode(boundMode);
    actor->setBlocked(document.blocked);
    result.actor = actor;
    return result;
}

ActorDocument extractActorDocument(const ActorNode& actor)
{
    const ActorDefinition* definition = actor.getDefinition().get();
    if (!definition) return ActorDocument();
    ActorDocument document = makeDocument(*definition);
    if (!actor.getName().empty()) document.name = actor.getName();
    document.preTranslation = toGlm(actor.getPreTranslation());
    document.preRotation = toGlm(actor.getPreRotation());
    document.postTranslation = toGlm(actor.getPostTranslation());
    document.postRotation = toGlm(actor.getPostRotation());
    document.blocked = actor.getBlocked();
    document.boundsCoverRotations = actor.getBoundMode() == ActorNode::BOUND_COVERS_ROTATIONS;
    addCullAndUpdatePolicy(actor, document);

    for (unsigned dof = 0; dof < definition->getNumDofs(); ++dof)
    {
        const double value = actor.getDof(dof);
        if (value != definition->getDofDefault(dof))
            document.joints[definition->getDofJoint(dof)].values[static_cast<unsigned>(definition->getDofType(dof))] =
                value;
    }
    for (unsigned j = 0; j < actor.getNumSkeletonNodes() && j < document.joints.size(); ++j)
    {
        const SkeletonNode* node = actor.getSkeletonNode(j);
        JointDocument& joint = document.joints[j];
        joint.hidden = node->getHidden();
        for (unsigned c = 0; c < node->getNumChildren(); ++c)
        {
            const osg::Node* child = node->getChild(c);
            if (dynamic_cast<const SkeletonNode*>(child)) continue;
            GeometryDescription geometry;
            if (describeGeometryNode(*child, geometry))
                joint.geometry.push_back(geometry);
            else
                OSG_WARN << "osgActor: writing actor '" << document.name << "': joint '" << joint.spec.name
                         << "' holds a " << child->className() << " named '" << child->getName()
                         << "' that a .actor file cannot describe; it is left out (write .osgt to keep it)"
                         << std::endl;
        }
    }

    addSkinFiles(actor, document);
    addClips(actor, document);
    addTrajectories(actor, document);
    addPlayers(actor, document);
    addIkChains(actor, document);

    std::string sections;
    if (actor.getUserValue(kSectionsUserValue, sections) && !sections.empty())
    {
        std::istringstream in(sections);
        std::string error;
        if (!parseSyntax(in, kSectionsUserValue, document.sections, error))
            OSG_WARN << "osgActor: writing actor '" << document.name << "': its kept sections are broken (" << error
                     << "); they are left out" << std::endl;
    }
    return document;
}

} // namespace osgActor
