#include <osgActor/core/detail/JointChildren.h>
#include <osgActor/core/detail/NameIndex>
#include <osgActor/io/ActorWriter>
#include <osgActor/io/AngleAxis>
#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

#include <cmath>
#include <string_view>

namespace osgActor {

namespace {

// Every number is written as the shortest text that reads back as exactly the double the document holds
// (text/Numbers), angles in degrees as the shortest text the reader turns into exactly the radians held, or in
// radians ("1rad") where no degrees do (text/Degrees): so reading what was written gives the same document. Each
// statement goes to the SyntaxWriter as it is made: nothing of the document is copied into another form first.

void writeVector(SyntaxWriter& w, const char* keyword, const glm::dvec3& v)
{
    w.begin(keyword).number(v.x).number(v.y).number(v.z).end();
}

/** "keyword angle axis" where an angle and an axis read back as exactly the rotation, "keyword quaternion w x y z"
  * otherwise. */
void writeRotation(SyntaxWriter& w, const char* keyword, const glm::dquat& rotation)
{
    w.begin(keyword);
    AngleAxis a;
    if (toExactAngleAxis(rotation, a)) w.number(a.degrees).number(a.axis[0]).number(a.axis[1]).number(a.axis[2]);
    else w.word("quaternion").number(rotation.w).number(rotation.x).number(rotation.y).number(rotation.z);
    w.end();
}

/** A statement of one number. */
void writeNumber(SyntaxWriter& w, const char* keyword, double value) { w.begin(keyword).number(value).end(); }

/** A statement of one word (an enum's name). */
void writeWord(SyntaxWriter& w, const char* keyword, const char* value) { w.begin(keyword).word(value).end(); }

/** A statement without arguments (a flag). */
void writeFlag(SyntaxWriter& w, const char* keyword) { w.begin(keyword).end(); }

bool isZero(const glm::dvec3& v) { return v.x == 0.0 && v.y == 0.0 && v.z == 0.0; }

/** "keyword x y z" and "keyword angle axis" lines where they differ from what the reader takes when they are left
  * out (zero, the identity). */
void writePlacement(SyntaxWriter& w, const char* translationKeyword, const glm::dvec3& translation,
                    const char* rotationKeyword, const glm::dquat& rotation)
{
    if (!isZero(translation)) writeVector(w, translationKeyword, translation);
    if (!isIdentityRotation(rotation)) writeRotation(w, rotationKeyword, rotation);
}

void writeDof(SyntaxWriter& w, Dof dof, const DofSpec& spec, const std::optional<double>& value)
{
    w.begin("dof").word(dofName(dof));
    // Limits, default and value in degrees for a rotation, model units for a translation.
    auto add = [&](const char* key, double v) {
        w.word(key);
        if (isRotation(dof)) w.angle(v);
        else w.number(v);
    };
    if (std::isfinite(spec.min)) add("min", spec.min);
    if (std::isfinite(spec.max)) add("max", spec.max);
    if (spec.defaultValue != 0.0) add("default", spec.defaultValue);
    if (spec.weight != 1.0) w.word("weight").number(spec.weight);
    if (value) add("value", *value);
    w.end();
}

void writeGeometry(SyntaxWriter& w, const GeometryDescription& g)
{
    if (g.kind == GeometryKind::Model)
    {
        w.begin("model").quoted(g.file);
        writePlacement(w, "position", g.position, "rotation", g.rotation);
        if (g.scale != 1.0) writeNumber(w, "scale", g.scale);
        w.end();
        return;
    }
    w.begin("shape").word(geometryKindName(g.kind));
    if (g.kind == GeometryKind::Box) writeVector(w, "size", g.size);
    else writeNumber(w, "radius", g.radius);
    if (g.kind != GeometryKind::Box && g.kind != GeometryKind::Sphere) writeNumber(w, "height", g.height);
    writePlacement(w, "position", g.position, "rotation", g.rotation);
    w.begin("color").number(g.color.r).number(g.color.g).number(g.color.b);
    if (g.color.a != 1.0) w.number(g.color.a);
    w.end();
    w.end();
}

/** "file "walk.bvh"" with a block of the options that differ from MotionFileOptions' defaults, if any. */
void writeClipFile(SyntaxWriter& w, const std::string& file, const MotionFileOptions& options)
{
    const MotionFileOptions defaults;
    w.begin("file").quoted(file);
    if (!options.skeletonFile.empty()) w.begin("skeleton").quoted(options.skeletonFile).end();
    if (!options.animation.empty()) w.begin("animation").quoted(options.animation).end();
    if (options.scale != defaults.scale) writeNumber(w, "scale", options.scale);
    if (options.fileUpAxis != defaults.fileUpAxis) writeWord(w, "up", upAxisName(options.fileUpAxis));
    if (options.dropFirstFrame) writeFlag(w, "drop_first_frame");
    if (options.absoluteRootPosition) writeFlag(w, "absolute_root_position");
    if (options.amcFrameRate != defaults.amcFrameRate) writeNumber(w, "frame_rate", options.amcFrameRate);
    w.end();
}

/** A clip's motion as a frame rate, a channel list and one line per frame. */
void writeUniformFrames(SyntaxWriter& w, const Clip& clip)
{
    writeNumber(w, "frame_rate", clip.getFrameRate());
    w.begin("channels");
    for (unsigned c = 0; c < clip.getNumChannels(); ++c) w.name(clip.getChannel(c).target);
    w.end();
    for (unsigned f = 0; f < clip.getNumFrames(); ++f)
    {
        w.begin("frame");
        for (unsigned c = 0; c < clip.getNumChannels(); ++c)
        {
            if (clip.getChannel(c).angular) w.angle(clip.getFrame(f)[c]);
            else w.number(clip.getFrame(f)[c]);
        }
        w.end();
    }
}

/** A clip's motion as one block of keys per channel. */
void writeChannelKeys(SyntaxWriter& w, const Clip& clip)
{
    for (unsigned c = 0; c < clip.getNumChannels(); ++c)
    {
        const ClipChannel& channel = clip.getChannel(c);
        w.begin("channel").name(channel.target).openBlock();
        if (channel.interpolation != Interpolation::Linear)
            writeWord(w, "interpolation", interpolationName(channel.interpolation));
        for (unsigned k = 0; k < clip.getNumKeys(c); ++k)
        {
            w.begin("key").number(clip.getKeyTime(c, k));
            if (channel.angular) w.angle(clip.getKeyValue(c, k));
            else w.number(clip.getKeyValue(c, k));
            w.end();
        }
        w.end();
    }
}

/** A clip as channel blocks of keys, as a frame rate, a channel list and one line per frame, or as the file it is
  * read from; "play" first when the actor plays it. */
void writeClip(SyntaxWriter& w, const ClipDocument& document)
{
    w.begin("clip").name(document.name()).openBlock();
    if (document.play) writeWord(w, "play", playModeName(document.playMode));
    if (!document.file.empty())
    {
        writeClipFile(w, document.file, document.fileOptions);
        if (document.retarget.enabled) writeClipRetarget(w, document.retarget);
    }
    else if (document.clip->isUniform()) writeUniformFrames(w, *document.clip);
    else writeChannelKeys(w, *document.clip);
    w.end();
}

/** "ikchain name { ... }": root, effector and solver always, the rest where it differs from the defaults. */
void writeIkChain(SyntaxWriter& w, const IkChainSpec& spec)
{
    w.begin("ikchain").name(spec.name).openBlock();
    w.begin("root").name(spec.rootJoint).end();
    w.begin("effector").name(spec.effectorJoint).end();
    if (!isZero(spec.effectorOffset)) writeVector(w, "effector_offset", spec.effectorOffset);
    writeWord(w, "solver", ikSolverName(spec.solver));
    if (spec.maxIterations != kDefaultIkIterations)
        w.begin("iterations").word(std::to_string(spec.maxIterations)).end();
    if (spec.tolerance != kDefaultIkTolerance) writeNumber(w, "tolerance", spec.tolerance);
    for (const IkWeightSpec& weight : spec.jointWeights)
        w.begin("joint_weight").name(weight.name).number(weight.weight).end();
    for (const IkWeightSpec& weight : spec.dofWeights)
        w.begin("dof_weight").name(weight.name).number(weight.weight).end();
    w.end();
}

/** Writes joints nested in their parents. Its memory is a few numbers per joint (which joints are written, each
  * joint's place by name, each joint's children), whatever the joints hold. */
class JointTreeWriter
{
public:
    JointTreeWriter(SyntaxWriter& writer, const ActorDocument& document)
        : _writer(writer), _document(document), _written(document.joints.size(), false), _byName(namesOf(document)),
          _children(parentsOf(document, _byName))
    {
    }

    void write()
    {
        // Roots first, then joints whose parent is unknown, then whatever a cycle or the nesting bound left unwritten.
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (_document.joints[j].spec.parent.empty()) writeJoint(j, false, 0);
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (!_written[j] && indexOf(_document.joints[j].spec.parent) < 0) writeJoint(j, true, 0);
        for (std::size_t j = 0; j < _document.joints.size(); ++j)
            if (!_written[j]) writeJoint(j, true, 0);
    }

private:
    void writeJoint(std::size_t j, bool withParent, unsigned depth)
    {
        _written[j] = true;
        const JointDocument& joint = _document.joints[j];
        SyntaxWriter& w = _writer;
        w.begin("joint").name(joint.spec.name);
        if (withParent) w.begin("parent").name(joint.spec.parent).end();
        writePlacement(w, "offset", joint.spec.translation, "rotation", joint.spec.rotation);
        if (joint.spec.eulerOrder != EulerOrder::XYZ) writeWord(w, "euler", eulerOrderName(joint.spec.eulerOrder));
        if (joint.spec.translationMode != TranslationMode::AfterRotation)
            writeWord(w, "translation_mode", translationModeName(joint.spec.translationMode));
        for (unsigned d = 0; d < kNumDofTypes; ++d)
            if (joint.spec.dofs[d].active) writeDof(w, static_cast<Dof>(d), joint.spec.dofs[d], joint.values[d]);
        if (joint.hidden) writeFlag(w, "hidden");
        for (const GeometryDescription& g : joint.geometry) writeGeometry(w, g);
        // Below kMaxWrittenJointNesting, children are written at the actor's level with a 'parent' statement
        // instead: the reader refuses blocks nested 200 deep, a chain of thousands of joints (a 'parent' chain in a
        // .actor file, an ASF hierarchy) would overflow the stack here, and each level indents every line below it.
        if (depth + 1 < kMaxWrittenJointNesting)
            for (unsigned child : _children.of(static_cast<unsigned>(j)))
                if (!_written[child]) writeJoint(child, false, depth + 1);
        w.end();
    }

    /** The index of the joint of a name (the first of a name given twice), or -1. */
    int indexOf(std::string_view name) const { return _byName.find(name, JointName{_document}); }

    /** Joint place's name, for the NameIndex over the document's joints. */
    struct JointName
    {
        const ActorDocument& document;
        std::string_view operator()(std::size_t place) const { return document.joints[place].spec.name; }
    };

    static NameIndex namesOf(const ActorDocument& document)
    {
        NameIndex byName;
        byName.build(document.joints.size(), JointName{document});
        return byName;
    }

    /** Each joint's children, from each joint's parent: none for a root, a parent not in the document, or a joint its
      * own parent. */
    static detail::JointChildren parentsOf(const ActorDocument& document, const NameIndex& byName)
    {
        std::vector<int> parents(document.joints.size(), -1);
        for (std::size_t j = 0; j < document.joints.size(); ++j)
        {
            const int parent = byName.find(document.joints[j].spec.parent, JointName{document});
            if (parent >= 0 && static_cast<std::size_t>(parent) != j) parents[j] = parent;
        }
        return detail::JointChildren(parents);
    }

    SyntaxWriter& _writer;
    const ActorDocument& _document;
    std::vector<bool> _written;
    NameIndex _byName;
    detail::JointChildren _children;
};

/** A trajectory as its player's state ("play" for a player that plays or has another mode than once, "paused" for
  * one that waits, "speed") and one "key time x y z heading" line per key, or as the file it is read from. */
void writeTrajectory(SyntaxWriter& w, const TrajectoryDocument& document)
{
    w.begin("trajectory").name(document.name()).openBlock();
    if (document.play || document.playMode != PlayMode::Once) writeWord(w, "play", playModeName(document.playMode));
    if (!document.play && document.playMode != PlayMode::Once) writeFlag(w, "paused");
    if (document.speed != 1.0) writeNumber(w, "speed", document.speed);
    if (!document.file.empty()) w.begin("file").quoted(document.file).end();
    else
        for (const TrajectoryKey& key : document.trajectory->getKeys())
            w.begin("key")
                .number(key.time)
                .number(key.position.x)
                .number(key.position.y)
                .number(key.position.z)
                .angle(key.heading)
                .end();
    w.end();
}

/** "update_policy { ... }": the fields that differ from ActorNode's defaults. */
void writeUpdatePolicy(SyntaxWriter& w, const UpdatePolicyDocument& policy)
{
    const UpdatePolicyDocument defaults;
    w.begin("update_policy").openBlock();
    if (policy.onlyWhenSeen) writeFlag(w, "only_when_seen");
    if (policy.maxDistance != defaults.maxDistance) writeNumber(w, "max_distance", policy.maxDistance);
    if (policy.halfRateBelowPixels != defaults.halfRateBelowPixels)
        writeNumber(w, "half_rate_below_pixels", policy.halfRateBelowPixels);
    if (policy.quarterRateBelowPixels != defaults.quarterRateBelowPixels)
        writeNumber(w, "quarter_rate_below_pixels", policy.quarterRateBelowPixels);
    w.end();
}

/** A player: its clip or trajectory, then only the state that differs from a new player's ("play" for a player that
  * plays or has another mode than a new one, "paused" for one that waits), a clip player's DOF selection last. */
void writePlayer(SyntaxWriter& w, const PlayerDocument& document)
{
    const PlayerDocument defaults;
    w.begin("player").name(document.name).openBlock();
    if (document.playsTrajectory()) w.begin("trajectory").name(document.trajectory).end();
    else w.begin("clip").name(document.clip).end();
    if (document.playing || document.playMode != document.defaultPlayMode())
        writeWord(w, "play", playModeName(document.playMode));
    if (!document.playing) writeFlag(w, "paused");
    auto number = [&](const char* keyword, double value, double defaultValue) {
        if (value != defaultValue) writeNumber(w, keyword, value);
    };
    if (document.time) writeNumber(w, "time", *document.time);
    number("speed", document.speed, defaults.speed);
    number("weight", document.weight, defaults.weight);
    if (!document.enabled) writeFlag(w, "disabled");
    if (!document.playsTrajectory())
    {
        number("fade", document.fade, defaults.fade);
        if (document.rootMotion != defaults.rootMotion || !document.rootJoint.empty())
        {
            w.begin("root_motion").word(rootMotionName(document.rootMotion));
            if (!document.rootJoint.empty()) w.name(document.rootJoint);
            w.end();
        }
        number("sway_window", document.swayWindow, defaults.swayWindow);
        for (const auto& dofWeight : document.dofWeights)
            w.begin("dof").name(dofWeight.first).number(dofWeight.second).end();
    }
    w.end();
}

} // namespace

void writeActorBlock(SyntaxWriter& w, const ActorDocument& document)
{
    writePlacement(w, "pre_translation", document.preTranslation, "pre_rotation", document.preRotation);
    writePlacement(w, "post_translation", document.postTranslation, "post_rotation", document.postRotation);
    if (document.blocked) writeFlag(w, "blocked");
    if (!document.boundsCoverRotations) writeWord(w, "bounds", boundsName(document.boundsCoverRotations));
    if (document.cullNodeByNode) writeWord(w, "cull", cullModeName(true));
    if (!document.updatePolicy.isDefault()) writeUpdatePolicy(w, document.updatePolicy);
    JointTreeWriter(w, document).write();
    for (const SkinFileDocument& skin : document.skinFiles) w.begin("skin").quoted(skin.file).end();
    for (const ClipDocument& clip : document.clips)
        if (clip.clip || !clip.file.empty()) writeClip(w, clip);
    for (const TrajectoryDocument& trajectory : document.trajectories)
        if (trajectory.trajectory || !trajectory.file.empty()) writeTrajectory(w, trajectory);
    for (const PlayerDocument& player : document.players) writePlayer(w, player);
    for (const IkChainDocument& chain : document.ikChains) writeIkChain(w, chain.spec);
    w.write(document.sections);
}

void writeActor(std::ostream& out, const ActorDocument& document)
{
    out << "# An osgActor actor (docs/actor-format.md): angles in degrees, lengths in model units.\n";
    SyntaxWriter w(out);
    w.begin("osgactor").word(std::to_string(ActorDocument::kFormatVersion)).end();
    w.begin("actor").name(document.name).openBlock();
    writeActorBlock(w, document);
    w.end();
}

} // namespace osgActor
