#include <osgActor/io/DocumentDifference>
#include <osgActor/text/Numbers>

namespace osgActor {

namespace {

std::string text(double v) { return formatNumber(v); }
std::string text(float v) { return formatNumber(v); }
std::string text(const glm::dvec3& v) { return text(v.x) + " " + text(v.y) + " " + text(v.z); }
std::string text(const glm::dvec4& v) { return text(v.x) + " " + text(v.y) + " " + text(v.z) + " " + text(v.w); }
std::string text(const glm::dquat& q) { return text(q.w) + " " + text(q.x) + " " + text(q.y) + " " + text(q.z); }
std::string text(const std::string& s) { return "'" + s + "'"; }
std::string text(bool b) { return b ? "yes" : "no"; }
std::string text(unsigned n) { return std::to_string(n); }
std::string text(const std::optional<double>& v) { return v ? text(*v) : "none"; }
template <class Enum>
std::string text(Enum e)
{
    return std::to_string(static_cast<int>(e));
}

bool same(double a, double b) { return a == b; }
bool same(const glm::dquat& a, const glm::dquat& b)
{
    return (a.w == b.w && a.x == b.x && a.y == b.y && a.z == b.z) ||
           (a.w == -b.w && a.x == -b.x && a.y == -b.y && a.z == -b.z);
}
template <class T>
bool same(const T& a, const T& b)
{
    return a == b;
}

/** Collects the first difference, each under the path of what holds it ("clip 'walk': channel 2: key 3: time"). */
class Differ
{
public:
    bool found() const { return !_difference.empty(); }
    const std::string& difference() const { return _difference; }

    template <class T>
    void field(const std::string& where, const T& a, const T& b)
    {
        if (found() || same(a, b)) return;
        _difference = where + ": " + text(a) + " against " + text(b);
    }

    /** The counts of two lists; false (with the difference) when they differ. */
    bool count(const std::string& where, std::size_t a, std::size_t b)
    {
        if (found()) return false;
        if (a == b) return true;
        _difference = where + ": " + std::to_string(a) + " against " + std::to_string(b);
        return false;
    }

    void joint(const std::string& where, const JointSpec& a, const JointSpec& b)
    {
        field(where + "name", a.name, b.name);
        field(where + "parent", a.parent, b.parent);
        field(where + "offset", a.translation, b.translation);
        field(where + "rotation", a.rotation, b.rotation);
        field(where + "euler order", a.eulerOrder, b.eulerOrder);
        field(where + "translation mode", a.translationMode, b.translationMode);
        for (unsigned d = 0; d < kNumDofTypes; ++d)
        {
            const std::string dof = where + "dof " + dofName(static_cast<Dof>(d)) + ": ";
            field(dof + "active", a.dofs[d].active, b.dofs[d].active);
            field(dof + "min", a.dofs[d].min, b.dofs[d].min);
            field(dof + "max", a.dofs[d].max, b.dofs[d].max);
            field(dof + "default", a.dofs[d].defaultValue, b.dofs[d].defaultValue);
            field(dof + "weight", a.dofs[d].weight, b.dofs[d].weight);
        }
    }

    void geometry(const std::string& where, const GeometryDescription& a, const GeometryDescription& b)
    {
        field(where + "kind", a.kind, b.kind);
        field(where + "size", a.size, b.size);
        field(where + "radius", a.radius, b.radius);
        field(where + "height", a.height, b.height);
        field(where + "file", a.file, b.file);
        field(where + "position", a.position, b.position);
        field(where + "rotation", a.rotation, b.rotation);
        field(where + "scale", a.scale, b.scale);
        field(where + "color", a.color, b.color);
    }

    void clip(const std::string& where, const Clip& a, const Clip& b)
    {
        field(where + "name", a.getName(), b.getName());
        field(where + "uniform", a.isUniform(), b.isUniform());
        if (!count(where + "channels", a.getNumChannels(), b.getNumChannels()) || found()) return;
        for (unsigned c = 0; c < a.getNumChannels() && !found(); ++c)
        {
            const std::string channel = where + "channel " + std::to_string(c) + ": ";
            field(channel + "target", a.getChannel(c).target, b.getChannel(c).target);
            field(channel + "interpolation", a.getChannel(c).interpolation, b.getChannel(c).interpolation);
            field(channel + "angular", a.getChannel(c).angular, b.getChannel(c).angular);
            if (a.isUniform() || !count(channel + "keys", a.getNumKeys(c), b.getNumKeys(c))) continue;
            for (unsigned k = 0; k < a.getNumKeys(c) && !found(); ++k)
            {
                field(channel + "key " + std::to_string(k) + ": time", a.getKeyTime(c, k), b.getKeyTime(c, k));
                field(channel + "key " + std::to_string(k) + ": value", a.getKeyValue(c, k), b.getKeyValue(c, k));
            }
        }
        if (!a.isUniform() || found()) return;
        field(where + "frame rate", a.getFrameRate(), b.getFrameRate());
        if (!count(where + "frames", a.getNumFrames(), b.getNumFrames())) return;
        for (unsigned f = 0; f < a.getNumFrames() && !found(); ++f)
            for (unsigned c = 0; c < a.getNumChannels() && !found(); ++c)
                field(where + "frame " + std::to_string(f) + ": channel " + std::to_string(c), a.getFrame(f)[c],
                      b.getFrame(f)[c]);
    }

    void trajectory(const std::string& where, const Trajectory& a, const Trajectory& b)
    {
        field(where + "name", a.getName(), b.getName());
        if (!count(where + "keys", a.getKeys().size(), b.getKeys().size())) return;
        for (std::size_t k = 0; k < a.getKeys().size() && !found(); ++k)
        {
            const std::string key = where + "key " + std::to_string(k) + ": ";
            field(key + "time", a.getKeys()[k].time, b.getKeys()[k].time);
            field(key + "position", a.getKeys()[k].position, b.getKeys()[k].position);
            field(key + "heading", a.getKeys()[k].heading, b.getKeys()[k].heading);
        }
    }

    void motionFile(const std::string& where, const ClipDocument& a, const ClipDocument& b)
    {
        field(where + "file", a.file, b.file);
        const MotionFileOptions& x = a.fileOptions;
        const MotionFileOptions& y = b.fileOptions;
        field(where + "file name", x.name, y.name);
        field(where + "skeleton", x.skeletonFile, y.skeletonFile);
        field(where + "scale", x.scale, y.scale);
        field(where + "up", x.fileUpAxis, y.fileUpAxis);
        field(where + "drop_first_frame", x.dropFirstFrame, y.dropFirstFrame);
        field(where + "absolute_root_position", x.absoluteRootPosition, y.absoluteRootPosition);
        field(where + "ASF limits", x.applyAsfLimits, y.applyAsfLimits);
        field(where + "frame_rate", x.amcFrameRate, y.amcFrameRate);
        field(where + "retarget", a.retarget.enabled, b.retarget.enabled);
        field(where + "retarget's joint map", a.retarget.sourceMap, b.retarget.sourceMap);
        field(where + "retarget's ik", a.retarget.ik, b.retarget.ik);
    }

    void player(const std::string& where, const PlayerDocument& a, const PlayerDocument& b)
    {
        field(where + "name", a.name, b.name);
        field(where + "clip", a.clip, b.clip);
        field(where + "trajectory", a.trajectory, b.trajectory);
        field(where + "playing", a.playing, b.playing);
        field(where + "play mode", a.playMode, b.playMode);
        field(where + "time", a.time, b.time);
        field(where + "speed", a.speed, b.speed);
        field(where + "weight", a.weight, b.weight);
        field(where + "enabled", a.enabled, b.enabled);
        field(where + "fade", a.fade, b.fade);
        field(where + "root motion", a.rootMotion, b.rootMotion);
        field(where + "root joint", a.rootJoint, b.rootJoint);
        field(where + "sway window", a.swayWindow, b.swayWindow);
        if (!count(where + "dofs", a.dofWeights.size(), b.dofWeights.size())) return;
        for (std::size_t d = 0; d < a.dofWeights.size(); ++d)
        {
            field(where + "dof " + std::to_string(d) + ": name", a.dofWeights[d].first, b.dofWeights[d].first);
            field(where + "dof " + std::to_string(d) + ": weight", a.dofWeights[d].second, b.dofWeights[d].second);
        }
    }

    void weights(const std::string& where, const std::vector<IkWeightSpec>& a, const std::vector<IkWeightSpec>& b)
    {
        if (!count(where, a.size(), b.size())) return;
        for (std::size_t w = 0; w < a.size(); ++w)
        {
            field(where + " " + std::to_string(w) + ": name", a[w].name, b[w].name);
            field(where + " " + std::to_string(w) + ": weight", a[w].weight, b[w].weight);
        }
    }

    void ikChain(const std::string& where, const IkChainSpec& a, const IkChainSpec& b)
    {
        field(where + "name", a.name, b.name);
        field(where + "root", a.rootJoint, b.rootJoint);
        field(where + "effector", a.effectorJoint, b.effectorJoint);
        field(where + "effector offset", a.effectorOffset, b.effectorOffset);
        field(where + "solver", a.solver, b.solver);
        field(where + "iterations", a.maxIterations, b.maxIterations);
        field(where + "tolerance", a.tolerance, b.tolerance);
        weights(where + "joint weights", a.jointWeights, b.jointWeights);
        weights(where + "dof weights", a.dofWeights, b.dofWeights);
    }

    void statements(const std::string& where, const std::vector<SyntaxStatement>& a,
                    const std::vector<SyntaxStatement>& b)
    {
        if (!count(where + "statements", a.size(), b.size())) return;
        for (std::size_t s = 0; s < a.size() && !found(); ++s)
        {
            const std::string statement = where + "statement " + std::to_string(s) + ": ";
            field(statement + "keyword", a[s].keyword, b[s].keyword);
            field(statement + "block", a[s].hasBlock, b[s].hasBlock);
            if (!count(statement + "arguments", a[s].arguments.size(), b[s].arguments.size())) return;
            for (std::size_t i = 0; i < a[s].arguments.size(); ++i)
            {
                field(statement + "argument", a[s].arguments[i].text, b[s].arguments[i].text);
                field(statement + "quoted", a[s].arguments[i].quoted, b[s].arguments[i].quoted);
            }
            statements(statement, a[s].children, b[s].children);
        }
    }

private:
    std::string _difference;
};

} // namespace

std::string documentDifference(const ActorDocument& a, const ActorDocument& b)
{
    Differ d;
    d.field("actor name", a.name, b.name);
    if (d.count("joints", a.joints.size(), b.joints.size()))
        for (std::size_t j = 0; j < a.joints.size() && !d.found(); ++j)
        {
            const JointDocument& x = a.joints[j];
            const JointDocument& y = b.joints[j];
            const std::string where = "joint " + text(x.spec.name) + ": ";
            d.joint(where, x.spec, y.spec);
            for (unsigned v = 0; v < kNumDofTypes; ++v)
                d.field(where + "value of " + dofName(static_cast<Dof>(v)), x.values[v], y.values[v]);
            d.field(where + "hidden", x.hidden, y.hidden);
            if (!d.count(where + "geometry", x.geometry.size(), y.geometry.size())) break;
            for (std::size_t g = 0; g < x.geometry.size(); ++g)
                d.geometry(where + "geometry " + std::to_string(g) + ": ", x.geometry[g], y.geometry[g]);
        }
    d.field("pre_translation", a.preTranslation, b.preTranslation);
    d.field("pre_rotation", a.preRotation, b.preRotation);
    d.field("post_translation", a.postTranslation, b.postTranslation);
    d.field("post_rotation", a.postRotation, b.postRotation);
    d.field("blocked", a.blocked, b.blocked);
    d.field("bounds cover rotations", a.boundsCoverRotations, b.boundsCoverRotations);
    d.field("cull node by node", a.cullNodeByNode, b.cullNodeByNode);
    d.field("update policy: only when seen", a.updatePolicy.onlyWhenSeen, b.updatePolicy.onlyWhenSeen);
    d.field("update policy: max distance", a.updatePolicy.maxDistance, b.updatePolicy.maxDistance);
    d.field("update policy: half rate below pixels", a.updatePolicy.halfRateBelowPixels,
            b.updatePolicy.halfRateBelowPixels);
    d.field("update policy: quarter rate below pixels", a.updatePolicy.quarterRateBelowPixels,
            b.updatePolicy.quarterRateBelowPixels);
    if (d.count("clips", a.clips.size(), b.clips.size()))
        for (std::size_t c = 0; c < a.clips.size() && !d.found(); ++c)
        {
            const ClipDocument& x = a.clips[c];
            const ClipDocument& y = b.clips[c];
            const std::string where = "clip " + text(x.name()) + ": ";
            d.field(where + "play", x.play, y.play);
            d.field(where + "play mode", x.playMode, y.playMode);
            d.motionFile(where, x, y);
            d.field(where + "has motion", x.clip != nullptr, y.clip != nullptr);
            if (x.clip && y.clip) d.clip(where, *x.clip, *y.clip);
        }
    if (d.count("trajectories", a.trajectories.size(), b.trajectories.size()))
        for (std::size_t t = 0; t < a.trajectories.size() && !d.found(); ++t)
        {
            const TrajectoryDocument& x = a.trajectories[t];
            const TrajectoryDocument& y = b.trajectories[t];
            const std::string where = "trajectory " + text(x.name()) + ": ";
            d.field(where + "play", x.play, y.play);
            d.field(where + "play mode", x.playMode, y.playMode);
            d.field(where + "speed", x.speed, y.speed);
            d.field(where + "file", x.file, y.file);
            d.field(where + "file's trajectory name", x.fileTrajectoryName, y.fileTrajectoryName);
            d.field(where + "has keys", x.trajectory != nullptr, y.trajectory != nullptr);
            if (x.trajectory && y.trajectory) d.trajectory(where, *x.trajectory, *y.trajectory);
        }
    if (d.count("players", a.players.size(), b.players.size()))
        for (std::size_t p = 0; p < a.players.size(); ++p)
            d.player("player " + text(a.players[p].name) + ": ", a.players[p], b.players[p]);
    if (d.count("IK chains", a.ikChains.size(), b.ikChains.size()))
        for (std::size_t c = 0; c < a.ikChains.size(); ++c)
            d.ikChain("IK chain " + text(a.ikChains[c].spec.name) + ": ", a.ikChains[c].spec, b.ikChains[c].spec);
    d.statements("sections: ", a.sections, b.sections);
    return d.difference();
}

std::string definitionDifference(const ActorDefinition& a, const ActorDefinition& b)
{
    Differ d;
    d.field("actor name", a.getName(), b.getName());
    const ActorDefinitionBuilder x = toBuilder(a);
    const ActorDefinitionBuilder y = toBuilder(b);
    if (d.count("joints", x.getNumJoints(), y.getNumJoints()))
        for (unsigned j = 0; j < x.getNumJoints() && !d.found(); ++j)
            d.joint("joint " + text(x.getJoint(j).name) + ": ", x.getJoint(j), y.getJoint(j));
    return d.difference();
}

std::string clipDifference(const Clip& a, const Clip& b)
{
    Differ d;
    d.clip("clip " + text(a.getName()) + ": ", a, b);
    return d.difference();
}

std::string trajectoryDifference(const Trajectory& a, const Trajectory& b)
{
    Differ d;
    d.trajectory("trajectory " + text(a.getName()) + ": ", a, b);
    return d.difference();
}

} // namespace osgActor
