#include <osgActor/import/RiggedActorBuilder>

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ClipBuilder>
#include <osgActor/core/skin/SkinBuilder>
#include <osgActor/import/ChannelSampling>
#include <osgActor/import/EulerFit>
#include <osgActor/mocap/MocapImport>

#include <glm/ext/quaternion_geometric.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

namespace osgActor {

namespace {

/** Scales that differ from each other (or from 1) by less than this, relatively, are taken as equal. */
constexpr double kScaleTolerance = 1e-5;

bool nearlyEqual(double a, double b) { return std::abs(a - b) <= kScaleTolerance * std::max(std::abs(a), std::abs(b)); }

bool isUniform(const glm::dvec3& s) { return s.x > 0.0 && nearlyEqual(s.x, s.y) && nearlyEqual(s.x, s.z); }

const char* const kRotationDofNames[3] = {"rx", "ry", "rz"};
const char* const kTranslationDofNames[3] = {"tx", "ty", "tz"};

std::string nodePlace(const RiggedModel& model, int node)
{
    return "nodes[" + std::to_string(node) + "] '" + model.nodes[node].name + "'";
}

/** What the mapping decides for one joint of the definition. */
struct JointPlan
{
    int node = -1;
    int parentJoint = -1;
    /** Scene lengths to model lengths for this joint's translations (sigma(parent) / k). */
    double lengthScale = 1.0;
    /** The uniform scale carried down to its children (sigma, file units per model unit times k). */
    double carriedScale = 1.0;
    /** The scale its own frame leaves out, for what it carries (skins, meshes): lengthScale * S(node). */
    glm::dmat4 residual{1.0};
    bool rotates = false;
    bool translates = false;
    glm::dquat reference{1.0, 0.0, 0.0, 0.0};
    EulerOrder order = EulerOrder::XYZ;
    double restAngles[3] = {0.0, 0.0, 0.0}; // product order
    /** How far a rotation error of one radian moves what this joint carries (model units per radian). */
    double lever = 1.0;
};

class Mapping
{
public:
    Mapping(const std::shared_ptr<const RiggedModel>& model, const RiggedActorOptions& options, RiggedActor& result)
        : _model(*model), _options(options), _result(result)
    {
        _result.model = model;
    }

    bool run()
    {
        if (!chooseJoints()) return false;
        planScales();
        measureModel();
        planDofs();
        if (!buildDefinition()) return false;
        for (std::size_t a = 0; a < _model.animations.size(); ++a)
            if (!buildClip(a)) return false;
        return bindMeshes();
    }

private:
    void warn(const std::string& text) { _result.warnings.push_back(_model.sourceFile + ": " + text); }
    bool fail(const std::string& text)
    {
        _result.error = _model.sourceFile + ": " + text;
        return false;
    }

    // --- which nodes are joints, in which order ---

    bool inScene(int node) const
    {
        int root = node;
        while (_model.nodes[root].parent >= 0) root = _model.nodes[root].parent;
        return std::find(_model.sceneRoots.begin(), _model.sceneRoots.end(), root) != _model.sceneRoots.end();
    }

    /** Whether a primitive drawn at a node is skinned there. */
    bool isSkinnedAt(int node, const RiggedPrimitive& primitive) const
    {
        return _model.nodes[node].skin >= 0 && primitive.influencesPerVertex > 0;
    }

    bool chooseJoints()
    {
        const std::size_t count = _model.nodes.size();
        std::vector<char> wanted(count, 0);
        for (const RiggedSkin& skin : _model.skins)
            for (int joint : skin.joints) wanted[joint] = 1;
        for (const RiggedAnimation& animation : _model.animations)
            for (const AnimationChannel& channel : animation.channels)
                if (channel.path != AnimationPath::Scale) wanted[channel.node] = 1;
        for (std::size_t n = 0; n < count; ++n)
        {
            const RiggedNode& node = _model.nodes[n];
            if (node.mesh < 0 || !inScene(int(n))) continue;
            for (const RiggedPrimitive& primitive : _model.meshes[node.mesh].primitives)
                if (!isSkinnedAt(int(n), primitive)) wanted[n] = 1;
        }
        for (std::size_t n = 0; n < count; ++n)
            if (wanted[n])
                for (int a = _model.nodes[n].parent; a >= 0 && !wanted[a]; a = _model.nodes[a].parent) wanted[a] = 1;

        // Parents first: depth first from the roots, siblings in node order.
        std::vector<std::vector<int>> children(count);
        std::vector<int> roots;
        for (std::size_t n = 0; n < count; ++n)
        {
            if (!wanted[n]) continue;
            if (_model.nodes[n].parent < 0) roots.push_back(int(n));
            else children[_model.nodes[n].parent].push_back(int(n));
        }
        _jointOfNode.assign(count, -1);
        std::function<void(int, int)> visit = [&](int node, int parentJoint) {
            JointPlan plan;
            plan.node = node;
            plan.parentJoint = parentJoint;
            _jointOfNode[node] = int(_plans.size());
            _plans.push_back(plan);
            const int joint = _jointOfNode[node];
            for (int child : children[node]) visit(child, joint);
        };
        for (int root : roots) visit(root, -1);
        if (_plans.empty()) return fail("nothing to make an actor of: no skin, no animation and no mesh");
        _result.jointNodes.clear();
        for (const JointPlan& plan : _plans) _result.jointNodes.push_back(plan.node);
        return true;
    }

    bool hasChildJoint(unsigned joint) const
    {
        for (const JointPlan& plan : _plans)
            if (plan.parentJoint == int(joint)) return true;
        return false;
    }

    // --- static scale ---

    void planScales()
    {
        double k = 1.0;
        if (_options.rootScale == RootScale::AboveActor)
        {
            const glm::dvec3& s = _model.nodes[_plans.front().node].scale;
            if (isUniform(s)) k = (s.x + s.y + s.z) / 3.0;
        }
        _up = _options.zUp ? upAxisToZUp(UpAxis::Y) : glm::dquat(1.0, 0.0, 0.0, 0.0);
        _result.rootScale = k;
        _result.modelToScene = glm::mat4_cast(glm::inverse(_up));
        _result.modelToScene[0] *= k;
        _result.modelToScene[1] *= k;
        _result.modelToScene[2] *= k;
        for (unsigned j = 0; j < _plans.size(); ++j)
        {
            JointPlan& plan = _plans[j];
            const glm::dvec3& s = _model.nodes[plan.node].scale;
            const double parentScale = plan.parentJoint >= 0 ? _plans[plan.parentJoint].carriedScale : 1.0 / k;
            plan.lengthScale = parentScale;
            plan.residual = glm::dmat4(1.0);
            for (int axis = 0; axis < 3; ++axis) plan.residual[axis][axis] = parentScale * s[axis];
            double uniform = (s.x + s.y + s.z) / 3.0;
            if (!isUniform(s))
            {
                uniform = std::cbrt(std::abs(s.x * s.y * s.z));
                if (hasChildJoint(j))
                    warn(nodePlace(_model, plan.node) + ": its scale (" + std::to_string(s.x) + ", " +
                         std::to_string(s.y) + ", " + std::to_string(s.z) +
                         ") is not uniform; the joints below it take the uniform scale " + std::to_string(uniform));
            }
            plan.carriedScale = parentScale * uniform;
        }
    }

    /** Rest matrices of the joints in model space, and the model's height from them. */
    void measureModel()
    {
        _restModel.resize(_plans.size());
        glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
        for (unsigned j = 0; j < _plans.size(); ++j)
        {
            const RiggedNode& node = _model.nodes[_plans[j].node];
            glm::dmat4 local = glm::mat4_cast(node.rotation);
            local[3] = glm::dvec4(_plans[j].lengthScale * node.translation, 1.0);
            _restModel[j] = _plans[j].parentJoint >= 0 ? _restModel[_plans[j].parentJoint] * local
                                                       : glm::mat4_cast(_up) * local;
            low = glm::min(low, glm::dvec3(_restModel[j][3]));
            high = glm::max(high, glm::dvec3(_restModel[j][3]));
        }
        double height = std::max({high.x - low.x, high.y - low.y, high.z - low.z});
        if (!(height > 1e-12))
        {
            // One joint, or all at one point: the meshes' extent (as stored) instead.
            low = glm::dvec3(std::numeric_limits<double>::infinity());
            high = -low;
            for (const RiggedMesh& mesh : _model.meshes)
                for (const RiggedPrimitive& primitive : mesh.primitives)
                    for (const glm::vec3& p : primitive.positions)
                    {
                        low = glm::min(low, glm::dvec3(p));
                        high = glm::max(high, glm::dvec3(p));
                    }
            height = high.x >= low.x ? std::max({high.x - low.x, high.y - low.y, high.z - low.z}) : 0.0;
        }
        _result.modelHeight = height > 1e-12 ? height : 1.0;
        // Lever: the farthest joint below each joint, at least a tenth of the model (the skin it carries).
        for (unsigned j = 0; j < _plans.size(); ++j) _plans[j].lever = 0.1 * _result.modelHeight;
        for (unsigned j = 0; j < _plans.size(); ++j)
            for (int a = _plans[j].parentJoint; a >= 0; a = _plans[a].parentJoint)
                _plans[a].lever = std::max(_plans[a].lever,
                                           glm::length(glm::dvec3(_restModel[j][3]) - glm::dvec3(_restModel[a][3])));
    }

    // --- DOFs ---

    /** The exact rotations a joint takes in every clip: at each key time and between keys. */
    std::vector<glm::dquat> rotationSamples(int node) const
    {
        std::vector<glm::dquat> samples;
        for (const RiggedAnimation& animation : _model.animations)
            for (const AnimationChannel& channel : animation.channels)
            {
                if (channel.node != node || channel.path != AnimationPath::Rotation) continue;
                for (std::size_t k = 0; k < channel.times.size(); ++k)
                {
                    samples.push_back(sampleRotationChannel(channel, channel.times[k]));
                    if (k + 1 < channel.times.size())
                        samples.push_back(sampleRotationChannel(channel, 0.5 * (channel.times[k] + channel.times[k + 1])));
                }
            }
        return samples;
    }

    void planDofs()
    {
        std::vector<char> skinJoint(_model.nodes.size(), 0);
        for (const RiggedSkin& skin : _model.skins)
            for (int joint : skin.joints) skinJoint[joint] = 1;
        for (const RiggedAnimation& animation : _model.animations)
            for (const AnimationChannel& channel : animation.channels)
            {
                if (channel.path == AnimationPath::Scale) continue; // its node may be no joint (chooseJoints())
                JointPlan& plan = _plans[_jointOfNode[channel.node]];
                if (channel.path == AnimationPath::Rotation) plan.rotates = true;
                if (channel.path == AnimationPath::Translation) plan.translates = true;
            }
        for (JointPlan& plan : _plans)
        {
            const glm::dquat rest = _model.nodes[plan.node].rotation;
            plan.rotates = plan.rotates || skinJoint[plan.node];
            plan.reference = rest;
            if (!plan.rotates) continue;
            const std::vector<glm::dquat> samples = rotationSamples(plan.node);
            if (samples.empty()) continue; // rest = reference: all angles 0 in any order
            std::vector<glm::dquat> relative;
            for (const glm::dquat& q : samples) relative.push_back(glm::inverse(rest) * q);
            double margin = 0.0;
            plan.order = chooseEulerOrder(relative, &margin);
            if (margin < 0.2)
            {
                // Near gimbal lock relative to the rest: try the clips' mean rotation as the reference instead.
                glm::dquat mean(0.0, 0.0, 0.0, 0.0);
                for (const glm::dquat& q : samples) mean += glm::dot(q, samples.front()) < 0.0 ? -q : q;
                mean = glm::normalize(mean);
                relative.clear();
                for (const glm::dquat& q : samples) relative.push_back(glm::inverse(mean) * q);
                double meanMargin = 0.0;
                const EulerOrder meanOrder = chooseEulerOrder(relative, &meanMargin);
                if (meanMargin > margin)
                {
                    plan.reference = mean;
                    plan.order = meanOrder;
                    eulerAngles(glm::inverse(mean) * rest, plan.order, nullptr, plan.restAngles);
                }
            }
        }
    }

    bool buildDefinition()
    {
        ActorDefinitionBuilder builder(baseNameOf(_model.sourceFile));
        for (const JointPlan& plan : _plans)
        {
            const RiggedNode& node = _model.nodes[plan.node];
            JointSpec spec;
            spec.name = node.name;
            spec.translation = plan.lengthScale * node.translation;
            spec.rotation = plan.reference;
            if (plan.parentJoint >= 0) spec.parent = _model.nodes[_plans[plan.parentJoint].node].name;
            else
            {
                // A root's offset is in the actor's model space: turned up there.
                spec.translation = _up * spec.translation;
                spec.rotation = _up * spec.rotation;
            }
            spec.eulerOrder = plan.order;
            spec.translationMode = TranslationMode::BeforeRotation;
            if (plan.rotates)
            {
                unsigned axes[3];
                eulerOrderAxes(plan.order, axes);
                for (unsigned i = 0; i < 3; ++i)
                {
                    spec.dofs[axes[i]].active = true;
                    spec.dofs[axes[i]].defaultValue = plan.restAngles[i];
                }
            }
            if (plan.translates)
                for (unsigned axis = 0; axis < 3; ++axis) spec.dofs[3 + axis].active = true;
            builder.addJoint(spec);
        }
        const BuildResult built = builder.build();
        if (!built) return fail(built.error);
        _result.definition = built.definition;
        return true;
    }

    // --- clips ---

    /** Keys of one DOF triple (a joint's rotation or translation) resampled from one channel. */
    struct TripleKeys
    {
        std::vector<double> times;
        std::vector<glm::dvec3> values;
    };

    /** Samples a channel into keys of three DOFs: exact at the channel's key times; between LINEAR and CUBICSPLINE
      * keys, evenly spaced samples, as few as keep the linear interpolation of the DOFs within tolerance of the
      * exact curve (error(t, interpolated) says how far, in model units). value(t, previous) gives the exact DOF
      * values at t, continuous with previous. Returns the worst error left where the sample cap was reached. */
    double resample(const AnimationChannel& channel,
                    const std::function<glm::dvec3(double, const glm::dvec3&)>& value,
                    const std::function<double(double, const glm::dvec3&)>& error, const glm::dvec3& start,
                    TripleKeys& keys) const
    {
        const double tolerance = _options.resampleTolerance * _result.modelHeight;
        double worstLeft = 0.0;
        glm::dvec3 previous = start;
        const std::size_t count = channel.times.size();
        for (std::size_t k = 0; k < count; ++k)
        {
            const double t0 = channel.times[k];
            const glm::dvec3 v0 = value(t0, previous);
            keys.times.push_back(t0);
            keys.values.push_back(v0);
            previous = v0;
            if (k + 1 == count || channel.interpolation == KeyInterpolation::Step) continue;
            const double t1 = channel.times[k + 1];
            std::vector<double> times;
            std::vector<glm::dvec3> values;
            for (unsigned pieces = 1;; pieces *= 2)
            {
                // pieces + 1 samples from t0 to t1, each continuous with the one before.
                times.assign(1, t0);
                values.assign(1, v0);
                for (unsigned i = 1; i <= pieces; ++i)
                {
                    times.push_back(i == pieces ? t1 : t0 + (t1 - t0) * double(i) / double(pieces));
                    values.push_back(value(times.back(), values.back()));
                }
                double worst = 0.0;
                for (unsigned i = 0; i < pieces; ++i)
                    for (double u : {0.25, 0.5, 0.75})
                        worst = std::max(worst, error(times[i] + u * (times[i + 1] - times[i]),
                                                      values[i] + u * (values[i + 1] - values[i])));
                if (worst <= tolerance) break;
                if (pieces * 2 > _options.maxSamplesPerInterval)
                {
                    worstLeft = std::max(worstLeft, worst);
                    break;
                }
            }
            for (std::size_t i = 1; i + 1 < times.size(); ++i) // the inner samples (t1 is the next key)
            {
                keys.times.push_back(times[i]);
                keys.values.push_back(values[i]);
            }
            previous = values.back();
        }
        return worstLeft;
    }

    static Interpolation clipInterpolation(const AnimationChannel& channel)
    {
        return channel.interpolation == KeyInterpolation::Step ? Interpolation::Step : Interpolation::Linear;
    }

    void addTriple(ClipBuilder& clip, const std::string& joint, const char* const names[3], const unsigned slot[3],
                   Interpolation interpolation, const TripleKeys& keys) const
    {
        for (unsigned i = 0; i < 3; ++i)
        {
            const unsigned channel = clip.addChannel(joint + "." + names[slot[i]], interpolation);
            for (std::size_t k = 0; k < keys.times.size(); ++k) clip.addKey(channel, keys.times[k], keys.values[k][i]);
        }
    }

    void checkAnimatedScale(const RiggedAnimation& animation, std::size_t index, const AnimationChannel& channel)
    {
        const glm::dvec3& rest = _model.nodes[channel.node].scale;
        bool constant = true;
        for (std::size_t k = 0; k < channel.values.size() && constant; ++k)
        {
            for (int axis = 0; axis < 3; ++axis) constant = constant && nearlyEqual(channel.values[k][axis], rest[axis]);
            if (!channel.outTangents.empty())
                for (int axis = 0; axis < 3; ++axis)
                    constant = constant && std::abs(channel.inTangents[k][axis]) <= kScaleTolerance &&
                               std::abs(channel.outTangents[k][axis]) <= kScaleTolerance;
        }
        if (!constant)
            warn("animations[" + std::to_string(index) + "] '" + animation.name + "': the scale of " +
                 nodePlace(_model, channel.node) + " is animated; animated scale is not supported and its rest scale is kept");
    }

    bool buildClip(std::size_t index)
    {
        const RiggedAnimation& animation = _model.animations[index];
        ClipBuilder clip(animation.name);
        double worstLeft = 0.0;
        for (const AnimationChannel& channel : animation.channels)
        {
            // Scale is not animated (a warning); its node may be no joint at all (chooseJoints() leaves it out).
            if (channel.path == AnimationPath::Scale)
            {
                checkAnimatedScale(animation, index, channel);
                continue;
            }
            const JointPlan& plan = _plans[_jointOfNode[channel.node]];
            const std::string& joint = _model.nodes[plan.node].name;
            const glm::dquat toReference = glm::inverse(plan.reference);
            TripleKeys keys;
            if (channel.path == AnimationPath::Rotation)
            {
                const EulerOrder order = plan.order;
                auto value = [&](double t, const glm::dvec3& previous) {
                    double angles[3];
                    eulerAngles(toReference * sampleRotationChannel(channel, t), order, &previous[0], angles);
                    return glm::dvec3(angles[0], angles[1], angles[2]);
                };
                auto error = [&](double t, const glm::dvec3& angles) {
                    const glm::dquat exact = toReference * sampleRotationChannel(channel, t);
                    const double cosHalf = std::min(1.0, std::abs(glm::dot(exact, eulerRotation(order, &angles[0]))));
                    return 2.0 * std::acos(cosHalf) * plan.lever;
                };
                const glm::dvec3 rest(plan.restAngles[0], plan.restAngles[1], plan.restAngles[2]);
                worstLeft = std::max(worstLeft, resample(channel, value, error, rest, keys));
                unsigned axes[3];
                eulerOrderAxes(order, axes);
                addTriple(clip, joint, kRotationDofNames, axes, clipInterpolation(channel), keys);
            }
            else
            {
                const glm::dvec3 rest = _model.nodes[plan.node].translation;
                const double scale = plan.lengthScale;
                auto exact = [&](double t) { return toReference * (scale * (sampleVectorChannel(channel, t) - rest)); };
                auto value = [&](double t, const glm::dvec3&) { return exact(t); };
                auto error = [&](double t, const glm::dvec3& d) { return glm::length(exact(t) - d); };
                worstLeft = std::max(worstLeft, resample(channel, value, error, glm::dvec3(0.0), keys));
                const unsigned axes[3] = {0, 1, 2};
                addTriple(clip, joint, kTranslationDofNames, axes, clipInterpolation(channel), keys);
            }
        }
        if (worstLeft > 0.0)
            warn("animations[" + std::to_string(index) + "] '" + animation.name + "': resampled to within " +
                 std::to_string(worstLeft) + " model units of the file's curves (the sample cap was reached)");
        if (clip.getNumChannels() == 0)
        {
            warn("animations[" + std::to_string(index) + "] '" + animation.name + "' moves no joint and is left out");
            return true;
        }
        const ClipBuildResult built = clip.build();
        if (!built) return fail("animations[" + std::to_string(index) + "] '" + animation.name + "': " + built.error);
        _result.clips.push_back(built.clip);
        return true;
    }

    // --- meshes ---

    bool bindMeshes()
    {
        for (std::size_t m = 0; m < _model.meshes.size(); ++m)
            for (std::size_t p = 0; p < _model.meshes[m].primitives.size(); ++p)
                for (std::size_t n = 0; n < _model.nodes.size(); ++n)
                {
                    const RiggedNode& node = _model.nodes[n];
                    if (node.mesh != int(m) || !inScene(int(n))) continue;
                    const RiggedPrimitive& primitive = _model.meshes[m].primitives[p];
                    if (isSkinnedAt(int(n), primitive))
                    {
                        if (!bindSkin(int(m), int(p), int(n))) return false;
                        continue;
                    }
                    RigidBinding rigid;
                    rigid.mesh = int(m);
                    rigid.primitive = int(p);
                    rigid.node = int(n);
                    rigid.joint = unsigned(_jointOfNode[n]);
                    rigid.jointFromMesh = _plans[rigid.joint].residual;
                    _result.rigidMeshes.push_back(rigid);
                }
        return true;
    }

    /** Whether every vector is one the skin takes: unit length within a loose bound (normals, tangents' xyz), and a
      * tangent's w +-1. */
    template <class Vec>
    static bool usableDirections(const std::vector<Vec>& directions)
    {
        for (const Vec& d : directions)
        {
            const float length = glm::length(glm::vec3(d));
            if (!(length > 1e-6f)) return false;
            if constexpr (sizeof(Vec) == sizeof(glm::vec4))
                if (std::abs(d[3]) != 1.0f) return false;
        }
        return true;
    }

    bool bindSkin(int mesh, int primitiveIndex, int node)
    {
        const RiggedPrimitive& primitive = _model.meshes[mesh].primitives[primitiveIndex];
        const int fileSkin = _model.nodes[node].skin;
        const RiggedSkin& skin = _model.skins[fileSkin];
        SkinBuilder builder(_model.nodes[node].name + " " + primitive.place);
        for (std::size_t j = 0; j < skin.joints.size(); ++j)
        {
            const JointPlan& plan = _plans[_jointOfNode[skin.joints[j]]];
            builder.addJoint(_model.nodes[plan.node].name, plan.residual * skin.inverseBindMatrices[j]);
        }
        builder.setPositions(primitive.positions);
        if (usableDirections(primitive.normals)) builder.setNormals(primitive.normals);
        else if (!primitive.normals.empty())
            warn(primitive.place + ": a normal of zero length; the skin moves no normals");
        if (!primitive.normals.empty() && usableDirections(primitive.normals))
        {
            if (usableDirections(primitive.tangents)) builder.setTangents(primitive.tangents);
            else if (!primitive.tangents.empty())
                warn(primitive.place + ": a tangent of zero length or with w not +-1; the skin moves no tangents");
        }
        // Zero weights are glTF's padding, and may name any joint: only the others are influences.
        const unsigned count = primitive.influencesPerVertex;
        for (std::size_t v = 0; v < primitive.getNumVertices(); ++v)
            for (unsigned i = 0; i < count; ++i)
                if (primitive.weights[v * count + i] > 0.0f)
                    builder.addInfluence(unsigned(v), primitive.joints[v * count + i], primitive.weights[v * count + i]);
        const SkinBuildResult built = builder.build();
        if (!built) return fail(primitive.place + ": " + built.error);
        SkinnedPrimitive skinned;
        skinned.mesh = mesh;
        skinned.primitive = primitiveIndex;
        skinned.node = node;
        skinned.fileSkin = fileSkin;
        skinned.skin = built.skin;
        _result.skins.push_back(std::move(skinned));
        return true;
    }

    const RiggedModel& _model;
    const RiggedActorOptions& _options;
    RiggedActor& _result;
    std::vector<JointPlan> _plans;
    std::vector<int> _jointOfNode;
    std::vector<glm::dmat4> _restModel;
    /** The turn from the file's axes to the actor's model space at the roots (identity, or Y up to Z up). */
    glm::dquat _up{1.0, 0.0, 0.0, 0.0};
};

} // namespace

RiggedActor buildRiggedActor(const std::shared_ptr<const RiggedModel>& model, const RiggedActorOptions& options)
{
    RiggedActor result;
    if (!model)
    {
        result.error = "no model";
        return result;
    }
    if (!Mapping(model, options, result).run())
    {
        RiggedActor failed;
        failed.error = result.error;
        return failed;
    }
    return result;
}

} // namespace osgActor
