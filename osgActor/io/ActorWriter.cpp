#include <osgActor/core/detail/JointChildren.h>
#include <osgActor/io/ActorWriter>
#include <osgActor/io/AngleAxis>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

#include <cmath>
#include <string_view>
#include <unordered_map>

namespace osgActor {

namespace {

// Every number is written as the shortest text that reads back as exactly the double the document holds
// (text/Numbers), angles in degrees as the shortest text the reader turns into exactly the radians held, or in
// radians ("1rad") where no degrees do (text/Degrees): so reading what was written gives the same document.

SyntaxArgument word(const std::string& text) { return SyntaxArgument{text, false, 0}; }
SyntaxArgument nameArgument(const std::string& name) { return SyntaxArgument{name, needsQuotes(name), 0}; }
SyntaxArgument numberArgument(double value) { return word(formatNumber(value)); }
SyntaxArgument angleArgument(double radians) { return word(formatAngle(radians)); }

SyntaxStatement statement(const std::string& keyword, std::vector<SyntaxArgument> arguments = {})
{
    SyntaxStatement s;
    s.keyword = keyword;
    s.arguments = std::move(arguments);
    return s;
}

SyntaxStatement vectorStatement(const std::string& keyword, const glm::dvec3& v)
{
    return statement(keyword, {numberArgument(v.x), numberArgument(v.y), numberArgument(v.z)});
}

/** "keyword angle axis" where an angle and an axis read back as exactly the rotation, "keyword quaternion w x y z"
  * otherwise. */
SyntaxStatement rotationStatement(const std::string& keyword, const glm::dquat& rotation)
{
    AngleAxis a;
    if (toExactAngleAxis(rotation, a))
        return statement(keyword, {numberArgument(a.degrees), numberArgument(a.axis[0]), numberArgument(a.axis[1]),
                                   numberArgument(a.axis[2])});
    return statement(keyword, {word("quaternion"), numberArgument(rotation.w), numberArgument(rotation.x),
                               numberArgument(rotation.y), numberArgument(rotation.z)});
}

bool isZero(const glm::dvec3& v) { return v.x == 0.0 && v.y == 0.0 && v.z == 0.0; }

/** Appends "keyword x y z" and "keyword angle axis" lines where they differ from what the reader takes when they
  * are left out (zero, the identity). */
void addPlacement(std::vector<SyntaxStatement>& out, const std::string& translationKeyword,
                  const glm::dvec3& translation, const std::string& rotationKeyword, const glm::dquat& rotation)
{
    if (!isZero(translation)) out.push_back(vectorStatement(translationKeyword, translation));
    if (!isIdentityRotation(rotation)) out.push_back(rotationStatement(rotationKeyword, rotation));
}

SyntaxStatement dofStatement(Dof dof, const DofSpec& spec, const std::optional<double>& value)
{
    SyntaxStatement s = statement("dof", {word(dofName(dof))});
    auto add = [&](const char* key, const SyntaxArgument& v) {
        s.arguments.push_back(word(key));
        s.arguments.push_back(v);
    };
    // Limits, default and value in degrees for a rotation, model units for a translation.
    auto dofValue = [&](double v) { return isRotation(dof) ? angleArgument(v) : numberArgument(v); };
    if (std::isfinite(spec.min)) add("min", dofValue(spec.min));
    if (std::isfinite(spec.max)) add("max", dofValue(spec.max));
    if (spec.defaultValue != 0.0) add("default", dofValue(spec.defaultValue));
    if (spec.weight != 1.0) add("weight", numberArgument(spec.weight));
    if (value) add("value", dofValue(*value));
    return s;
}

SyntaxStatement geometryStatement(const GeometryDescription& g)
{
    SyntaxStatement s;
    if (g.kind == GeometryKind::Model)
    {
        s = statement("model", {SyntaxArgument{g.file, true, 0}});
        addPlacement(s.children, "position", g.position, "rotation", g.rotation);
        if (g.scale != 1.0) s.children.push_back(statement("scale", {numberArgument(g.scale)}));
    }
    else
    {
        s = statement("shape", {word(geometryKindName(g.kind))});
        if (g.kind == GeometryKind::Box) s.children.push_back(vectorStatement("size", g.size));
        else s.children.push_back(statement("radius", {numberArgument(g.radius)}));
        if (g.kind != GeometryKind::Box && g.kind != GeometryKind::Sphere)
            s.children.push_back(statement("height", {numberArgument(g.height)}));
        addPlacement(s.children, "position", g.position, "rotation", g.rotation);
        SyntaxStatement color = statement("color", {numberArgument(g.color.r), numberArgument(g.color.g),
                                                    numberArgument(g.color.b)});
        if (g.color.a != 1.0) color.arguments.push_back(numberArgument(g.color.a));
        s.children.push_back(color);
    }
    s.hasBlock = !s.children.empty();
    return s;
}

/** "file "walk.bvh"" with a block of the options that differ from MotionFileOptions' defaults, if any. */
SyntaxStatement clipFileStatement(const std::string& file, const MotionFileOptions& options)
{
    const MotionFileOptions defaults;
    SyntaxStatement s = statement("file", {SyntaxArgument{file, true, 0}});
    if (!options.skeletonFile.empty())
        s.children.push_back(statement("skeleton", {SyntaxArgument{options.skeletonFile, true, 0}}));
    if (!options.animation.empty())
        s.children.push_back(statement("animation", {SyntaxArgument{options.animation, true, 0}}));
    if (options.scale != defaults.scale) s.children.push_back(statement("scale", {numberArgument(options.scale)}));
    if (options.fileUpAxis != defaults.fileUpAxis)
        s.children.push_back(statement("up", {word(upAxisName(options.fileUpAxis))}));
    if (options.dropFirstFrame) s.children.push_back(statement("drop_first_frame"));
    if (options.absoluteRootPosition) s.children.push_back(statement("absolute_root_position"));
    if (options.amcFrameRate != defaults.amcFrameRate)
        s.children.push_back(statement("frame_rate", {numberArgument(options.amcFrameRate)}));
    s.hasBlock = !s.children.empty();
    return s;
}

/** A clip as channel blocks of keys, as a frame rate, a channel list and one line per frame, or as the file it is
  * read from; "play" first when the actor plays it. */
SyntaxStatement clipStatement(const ClipDocument& document)
{
    SyntaxStatement s = statement("clip", {nameArgument(document.name())});
    s.hasBlock = true;
    if (document.play) s.children.push_back(statement("play", {word(playModeName(document.playMode))}));
    if (!document.file.empty())
    {
        s.children.push_back(clipFileStatement(document.file, document.fileOptions));
        if (document.retarget.enabled) s.children.push_back(clipRetargetStatement(document.retarget));
        return s;
    }
    const Clip& clip = *document.clip;
    auto value = [&](unsigned channel, double v) {
        return clip.getChannel(channel).angular ? angleArgument(v) : numberArgument(v);
    };
    if (clip.isUniform())
    {
        s.children.push_back(statement("frame_rate", {numberArgument(clip.getFrameRate())}));
        SyntaxStatement channels = statement("channels");
        for (unsigned c = 0; c < clip.getNumChannels(); ++c)
            channels.arguments.push_back(nameArgument(clip.getChannel(c).target));
        s.children.push_back(channels);
        for (unsigned f = 0; f < clip.getNumFrames(); ++f)
        {
            SyntaxStatement frame = statement("frame");
            for (unsigned c = 0; c < clip.getNumChannels(); ++c)
                frame.arguments.push_back(value(c, clip.getFrame(f)[c]));
            s.children.push_back(frame);
        }
        return s;
    }
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
    {
        SyntaxStatement channel = statement("channel", {nameArgument(clip.getChannel(c).target)});
        channel.hasBlock = true;
        if (clip.getChannel(c).interpolation != Interpolation::Linear)
            channel.children.push_back(
                statement("interpolation", {word(interpolationName(clip.getChannel(c).interpolation))}));
        for (unsigned k = 0; k < clip.getNumKeys(c); ++k)
            channel.children.push_back(
                statement("key", {numberArgument(clip.getKeyTime(c, k)), value(c, clip.getKeyValue(c, k))}));
        s.children.push_back(channel);
    }
    return s;
}

/** "ikchain name { ... }": root, effector and solver always, the rest where it differs from the defaults. */
SyntaxStatement ikChainStatement(const IkChainSpec& spec)
{
    SyntaxStatement s = statement("ikchain", {nameArgument(spec.name)});
    s.children.push_back(statement("root", {nameArgument(spec.rootJoint)}));
    s.children.push_back(statement("effector", {nameArgument(spec.effectorJoint)}));
    if (!isZero(spec.effectorOffset)) s.children.push_back(vectorStatement("effector_offset", spec.effectorOffset));
    s.children.push_back(statement("solver", {word(ikSolverName(spec.solver))}));
    if (spec.maxIterations != kDefaultIkIterations)
        s.children.push_back(statement("iterations", {word(std::to_string(spec.maxIterations))}));
    if (spec.tolerance != kDefaultIkTolerance)
        s.children.push_back(statement("tolerance", {numberArgument(spec.tolerance)}));
    for (const IkWeightSpec& w : spec.jointWeights)
        s.children.push_back(statement("joint_weight", {nameArgument(w.name), numberArgument(w.weight)}));
    for (const IkWeightSpec& w : spec.dofWeights)
        s.children.push_back(statement("dof_weight", {nameArgument(w.name), numberArgument(w.weight)}));
    s.hasBlock = true;
    return s;
}

/** Writes joints nested in their parents. */
/** Joints nested in each other's blocks at most. */
constexpr unsigned kMaxNesting = 100;

class JointTreeWriter
{
public:
    explicit JointTreeWriter(const ActorDocument& document)
        : _document(document), _written(document.joints.size(), false), _byName(namesOf(document)),
          _children(parentsOf(document, _byName))
    {
    }

    void write(std::vector<SyntaxStatement>& out)
    {
        // Roots first, then joints whose parent is unknown, then whatever a cycle or the nesting bound left unwritten.
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (_document.joints[j].spec.parent.empty()) writeJoint(j, false, out, 0);
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (!_written[j] && !_byName.count(_document.joints[j].spec.parent)) writeJoint(j, true, out, 0);
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (!_written[j]) writeJoint(j, true, out, 0);
    }

private:
    void writeJoint(std::size_t j, bool withParent, std::vector<SyntaxStatement>& out, unsigned depth)
    {
        _written[j] = true;
        const JointDocument& joint = _document.joints[j];
        SyntaxStatement s = statement("joint", {nameArgument(joint.spec.name)});
        if (withParent) s.children.push_back(statement("parent", {nameArgument(joint.spec.parent)}));
        addPlacement(s.children, "offset", joint.spec.translation, "rotation", joint.spec.rotation);
        if (joint.spec.eulerOrder != EulerOrder::XYZ)
            s.children.push_back(statement("euler", {word(eulerOrderName(joint.spec.eulerOrder))}));
        if (joint.spec.translationMode != TranslationMode::AfterRotation)
            s.children.push_back(
                statement("translation_mode", {word(translationModeName(joint.spec.translationMode))}));
        for (unsigned d = 0; d < kNumDofTypes; ++d)
            if (joint.spec.dofs[d].active)
                s.children.push_back(dofStatement(static_cast<Dof>(d), joint.spec.dofs[d], joint.values[d]));
        if (joint.hidden) s.children.push_back(statement("hidden"));
        for (const GeometryDescription& g : joint.geometry) s.children.push_back(geometryStatement(g));
        // Below kMaxNesting, children are written at the actor's level with a 'parent' statement instead: the reader
        // refuses blocks nested 200 deep, and a chain of thousands of joints (a 'parent' chain in a .actor file, an
        // ASF hierarchy) would overflow the stack here.
        if (depth + 1 < kMaxNesting)
            for (unsigned child : _children.of(static_cast<unsigned>(j)))
                if (!_written[child]) writeJoint(child, false, s.children, depth + 1);
        s.hasBlock = !s.children.empty();
        out.push_back(std::move(s));
    }

    /** Each joint's index by name (the first of a name given twice, as a map's emplace keeps), viewing the
      * document's names. */
    static std::unordered_map<std::string_view, std::size_t> namesOf(const ActorDocument& document)
    {
        std::unordered_map<std::string_view, std::size_t> byName;
        byName.reserve(document.joints.size());
        for (std::size_t j = 0; j < document.joints.size(); ++j) byName.emplace(document.joints[j].spec.name, j);
        return byName;
    }

    /** Each joint's parent by index: -1 for a root, a parent not in the document, or a joint its own parent. */
    static detail::JointChildren parentsOf(const ActorDocument& document,
                                           const std::unordered_map<std::string_view, std::size_t>& byName)
    {
        std::vector<int> parents(document.joints.size(), -1);
        for (std::size_t j = 0; j < document.joints.size(); ++j)
        {
            const auto parent = byName.find(document.joints[j].spec.parent);
            if (parent != byName.end() && parent->second != j) parents[j] = static_cast<int>(parent->second);
        }
        return detail::JointChildren(parents);
    }

    const ActorDocument& _document;
    std::vector<bool> _written;
    std::unordered_map<std::string_view, std::size_t> _byName;
    detail::JointChildren _children;
};

} // namespace

/** A trajectory as its player's state ("play" for a player that plays or has another mode than once, "paused" for
  * one that waits, "speed") and one "key time x y z heading" line per key, or as the file it is read from. */
SyntaxStatement trajectoryStatement(const TrajectoryDocument& document)
{
    SyntaxStatement s = statement("trajectory", {nameArgument(document.name())});
    s.hasBlock = true;
    if (document.play || document.playMode != PlayMode::Once)
        s.children.push_back(statement("play", {word(playModeName(document.playMode))}));
    if (!document.play && document.playMode != PlayMode::Once) s.children.push_back(statement("paused"));
    if (document.speed != 1.0) s.children.push_back(statement("speed", {numberArgument(document.speed)}));
    if (!document.file.empty())
    {
        s.children.push_back(statement("file", {SyntaxArgument{document.file, true, 0}}));
        return s;
    }
    for (const TrajectoryKey& key : document.trajectory->getKeys())
        s.children.push_back(statement("key", {numberArgument(key.time), numberArgument(key.position.x),
                                               numberArgument(key.position.y), numberArgument(key.position.z),
                                               angleArgument(key.heading)}));
    return s;
}

/** A player: its clip or trajectory, then only the state that differs from a new player's ("play" for a player that
  * plays or has another mode than a new one, "paused" for one that waits), a clip player's DOF selection last. */
/** "update_policy { ... }": the fields that differ from ActorNode's defaults. */
SyntaxStatement updatePolicyStatement(const UpdatePolicyDocument& policy)
{
    const UpdatePolicyDocument defaults;
    SyntaxStatement s = statement("update_policy");
    s.hasBlock = true;
    if (policy.onlyWhenSeen) s.children.push_back(statement("only_when_seen"));
    if (policy.maxDistance != defaults.maxDistance)
        s.children.push_back(statement("max_distance", {numberArgument(policy.maxDistance)}));
    if (policy.halfRateBelowPixels != defaults.halfRateBelowPixels)
        s.children.push_back(statement("half_rate_below_pixels", {numberArgument(policy.halfRateBelowPixels)}));
    if (policy.quarterRateBelowPixels != defaults.quarterRateBelowPixels)
        s.children.push_back(statement("quarter_rate_below_pixels", {numberArgument(policy.quarterRateBelowPixels)}));
    return s;
}

SyntaxStatement playerStatement(const PlayerDocument& document)
{
    const PlayerDocument defaults;
    SyntaxStatement s = statement("player", {nameArgument(document.name)});
    s.hasBlock = true;
    if (document.playsTrajectory()) s.children.push_back(statement("trajectory", {nameArgument(document.trajectory)}));
    else s.children.push_back(statement("clip", {nameArgument(document.clip)}));
    if (document.playing || document.playMode != document.defaultPlayMode())
        s.children.push_back(statement("play", {word(playModeName(document.playMode))}));
    if (!document.playing) s.children.push_back(statement("paused"));
    auto number = [&](const char* keyword, double value, double defaultValue) {
        if (value != defaultValue) s.children.push_back(statement(keyword, {numberArgument(value)}));
    };
    if (document.time) s.children.push_back(statement("time", {numberArgument(*document.time)}));
    number("speed", document.speed, defaults.speed);
    number("weight", document.weight, defaults.weight);
    if (!document.enabled) s.children.push_back(statement("disabled"));
    if (document.playsTrajectory()) return s;
    number("fade", document.fade, defaults.fade);
    if (document.rootMotion != defaults.rootMotion || !document.rootJoint.empty())
    {
        SyntaxStatement rootMotion = statement("root_motion", {word(rootMotionName(document.rootMotion))});
        if (!document.rootJoint.empty()) rootMotion.arguments.push_back(nameArgument(document.rootJoint));
        s.children.push_back(rootMotion);
    }
    number("sway_window", document.swayWindow, defaults.swayWindow);
    for (const auto& dofWeight : document.dofWeights)
        s.children.push_back(statement("dof", {nameArgument(dofWeight.first), numberArgument(dofWeight.second)}));
    return s;
}

std::vector<SyntaxStatement> toSyntax(const ActorDocument& document)
{
    std::vector<SyntaxStatement> file;
    file.push_back(statement("osgactor", {word(std::to_string(ActorDocument::kFormatVersion))}));
    SyntaxStatement actor = statement("actor", {nameArgument(document.name)});
    actor.hasBlock = true;
    addPlacement(actor.children, "pre_translation", document.preTranslation, "pre_rotation", document.preRotation);
    addPlacement(actor.children, "post_translation", document.postTranslation, "post_rotation", document.postRotation);
    if (document.blocked) actor.children.push_back(statement("blocked"));
    if (!document.boundsCoverRotations)
        actor.children.push_back(statement("bounds", {word(boundsName(document.boundsCoverRotations))}));
    if (document.cullNodeByNode) actor.children.push_back(statement("cull", {word(cullModeName(true))}));
    if (!document.updatePolicy.isDefault()) actor.children.push_back(updatePolicyStatement(document.updatePolicy));
    JointTreeWriter(document).write(actor.children);
    for (const SkinFileDocument& skin : document.skinFiles)
        actor.children.push_back(statement("skin", {SyntaxArgument{skin.file, true, 0}}));
    for (const ClipDocument& clip : document.clips)
        if (clip.clip || !clip.file.empty()) actor.children.push_back(clipStatement(clip));
    for (const TrajectoryDocument& trajectory : document.trajectories)
        if (trajectory.trajectory || !trajectory.file.empty())
            actor.children.push_back(trajectoryStatement(trajectory));
    for (const PlayerDocument& player : document.players) actor.children.push_back(playerStatement(player));
    for (const IkChainDocument& chain : document.ikChains) actor.children.push_back(ikChainStatement(chain.spec));
    for (const SyntaxStatement& section : document.sections) actor.children.push_back(section);
    file.push_back(std::move(actor));
    return file;
}

void writeActor(std::ostream& out, const ActorDocument& document)
{
    out << "# An osgActor actor (docs/actor-format.md): angles in degrees, lengths in model units.\n";
    writeSyntax(out, toSyntax(document));
}

} // namespace osgActor
