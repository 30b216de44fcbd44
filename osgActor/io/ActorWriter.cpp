#include <osgActor/io/ActorNumbers>
#include <osgActor/io/ActorWriter>

#include <glm/ext/scalar_constants.hpp>

#include <cmath>
#include <limits>
#include <map>

namespace osgActor {

namespace {

constexpr double kDegreesPerRadian = 180.0 / glm::pi<double>();

SyntaxArgument word(const std::string& text) { return SyntaxArgument{text, false, 0}; }
SyntaxArgument nameArgument(const std::string& name) { return SyntaxArgument{name, quoteIfNeeded(name) != name, 0}; }
SyntaxArgument numberArgument(double value) { return word(formatNumber(value)); }

/** Key times, increasing as the reader requires: to 12 digits like every number, or exactly where 12 digits would
  * not come after the key before (keys closer than a part in 10^12). previous is what the key before reads back
  * as; updated. */
SyntaxArgument keyTimeArgument(double time, double& previous)
{
    std::string text = formatNumber(time);
    double readBack = 0.0;
    if (!parseNumber(text, readBack) || !(readBack > previous)) text = formatExactNumber(time);
    parseNumber(text, readBack);
    previous = readBack;
    return word(text);
}

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

SyntaxStatement rotationStatement(const std::string& keyword, const glm::dquat& rotation)
{
    const AngleAxis a = toAngleAxis(rotation);
    return statement(keyword, {numberArgument(a.degrees), numberArgument(a.axis[0]), numberArgument(a.axis[1]),
                               numberArgument(a.axis[2])});
}

bool isZero(const glm::dvec3& v)
{
    return formatNumber(v.x) == "0" && formatNumber(v.y) == "0" && formatNumber(v.z) == "0";
}

/** Appends "keyword x y z" and "keyword angle axis" lines where they differ from the identity. */
void addPlacement(std::vector<SyntaxStatement>& out, const std::string& translationKeyword,
                  const glm::dvec3& translation, const std::string& rotationKeyword, const glm::dquat& rotation)
{
    if (!isZero(translation)) out.push_back(vectorStatement(translationKeyword, translation));
    if (!isIdentityRotation(rotation)) out.push_back(rotationStatement(rotationKeyword, rotation));
}

SyntaxStatement dofStatement(Dof dof, const DofSpec& spec, const std::optional<double>& value)
{
    const double unit = isRotation(dof) ? kDegreesPerRadian : 1.0;
    SyntaxStatement s = statement("dof", {word(dofName(dof))});
    auto add = [&](const char* key, double v) {
        s.arguments.push_back(word(key));
        s.arguments.push_back(numberArgument(v));
    };
    if (std::isfinite(spec.min)) add("min", spec.min * unit);
    if (std::isfinite(spec.max)) add("max", spec.max * unit);
    if (formatNumber(spec.defaultValue) != "0") add("default", spec.defaultValue * unit);
    if (spec.weight != 1.0) add("weight", spec.weight);
    // Compared as written: a value one rounding step from its default (after a trip through another format)
    // is the default as far as the file can tell.
    if (value && formatNumber(*value * unit) != formatNumber(spec.defaultValue * unit)) add("value", *value * unit);
    return s;
}

SyntaxStatement geometryStatement(const GeometryDescription& g)
{
    SyntaxStatement s;
    if (g.kind == GeometryKind::Model)
    {
        s = statement("model", {SyntaxArgument{g.file, true, 0}});
        addPlacement(s.children, "position", g.position, "rotation", g.rotation);
        if (formatNumber(g.scale) != "1") s.children.push_back(statement("scale", {numberArgument(g.scale)}));
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
        if (formatNumber(g.color.a) != "1") color.arguments.push_back(numberArgument(g.color.a));
        s.children.push_back(color);
    }
    s.hasBlock = !s.children.empty();
    return s;
}

const char* interpolationName(Interpolation interpolation)
{
    switch (interpolation)
    {
    case Interpolation::Step: return "step";
    case Interpolation::Cubic: return "cubic";
    case Interpolation::Linear: break;
    }
    return "linear";
}

/** "file "walk.bvh"" with a block of the options that differ from MotionFileOptions' defaults, if any. */
SyntaxStatement clipFileStatement(const std::string& file, const MotionFileOptions& options)
{
    const MotionFileOptions defaults;
    SyntaxStatement s = statement("file", {SyntaxArgument{file, true, 0}});
    if (!options.skeletonFile.empty())
        s.children.push_back(statement("skeleton", {SyntaxArgument{options.skeletonFile, true, 0}}));
    if (options.scale != defaults.scale) s.children.push_back(statement("scale", {numberArgument(options.scale)}));
    if (options.fileUpAxis != defaults.fileUpAxis)
        s.children.push_back(statement("up", {word(options.fileUpAxis == UpAxis::Z ? "z" : "y")}));
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
    auto unit = [&](unsigned channel) { return clip.getChannel(channel).angular ? kDegreesPerRadian : 1.0; };
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
                frame.arguments.push_back(numberArgument(clip.getFrame(f)[c] * unit(c)));
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
        double previous = -std::numeric_limits<double>::infinity();
        for (unsigned k = 0; k < clip.getNumKeys(c); ++k)
            channel.children.push_back(statement("key", {keyTimeArgument(clip.getKeyTime(c, k), previous),
                                                         numberArgument(clip.getKeyValue(c, k) * unit(c))}));
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
        : _document(document), _written(document.joints.size(), false)
    {
        for (std::size_t j = 0; j < document.joints.size(); ++j) _byName.emplace(document.joints[j].spec.name, j);
        for (std::size_t j = 0; j < document.joints.size(); ++j)
        {
            const auto parent = _byName.find(document.joints[j].spec.parent);
            if (parent != _byName.end() && parent->second != j) _children[parent->second].push_back(j);
        }
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
        if (joint.spec.translationMode == TranslationMode::BeforeRotation)
            s.children.push_back(statement("translation_mode", {word("before_rotation")}));
        for (unsigned d = 0; d < kNumDofTypes; ++d)
            if (joint.spec.dofs[d].active)
                s.children.push_back(dofStatement(static_cast<Dof>(d), joint.spec.dofs[d], joint.values[d]));
        if (joint.hidden) s.children.push_back(statement("hidden"));
        for (const GeometryDescription& g : joint.geometry) s.children.push_back(geometryStatement(g));
        const auto children = _children.find(j);
        // Below kMaxNesting, children are written at the actor's level with a 'parent' statement instead: the reader
        // refuses blocks nested 200 deep, and a chain of thousands of joints (a 'parent' chain in a .actor file, an
        // ASF hierarchy) would overflow the stack here.
        if (children != _children.end() && depth + 1 < kMaxNesting)
            for (std::size_t child : children->second)
                if (!_written[child]) writeJoint(child, false, s.children, depth + 1);
        s.hasBlock = !s.children.empty();
        out.push_back(std::move(s));
    }

    const ActorDocument& _document;
    std::vector<bool> _written;
    std::map<std::string, std::size_t> _byName;
    std::map<std::size_t, std::vector<std::size_t>> _children;
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
    double previous = -std::numeric_limits<double>::infinity();
    for (const TrajectoryKey& key : document.trajectory->getKeys())
        s.children.push_back(statement("key", {keyTimeArgument(key.time, previous), numberArgument(key.position.x),
                                               numberArgument(key.position.y), numberArgument(key.position.z),
                                               numberArgument(key.heading * kDegreesPerRadian)}));
    return s;
}

/** A player: its clip or trajectory, then only the state that differs from a new player's ("play" for a player that
  * plays or has another mode than a new one, "paused" for one that waits), a clip player's DOF selection last. */
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
    if (!document.boundsCoverRotations) actor.children.push_back(statement("bounds", {word("follows_pose")}));
    JointTreeWriter(document).write(actor.children);
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
