#include <osgActor/OsgAnimationImport>

#include "OsgAnimationScene"

#include <osgActor/GlmOsg>
#include <osgActor/import/RiggedModelFile>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osgAnimation/Bone>
#include <osgAnimation/RigGeometry>
#include <osgAnimation/Skeleton>
#include <osgAnimation/UpdateMatrixTransform>
#include <osgDB/Registry>

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace osgActor {

namespace osganimation {

std::string describe(const osg::Object& object)
{
    return std::string(object.className()) + " '" + object.getName() + "'";
}

namespace {

/** How far (a fraction of the model's height) a sampled animated transform may stray from osgAnimation's between
  * the samples: RiggedActorOptions' default resampling tolerance. */
constexpr double kTolerance = 1e-5;

/** The deepest scene graph the converter follows (a deeper one is refused, never overflows the stack). */
constexpr std::size_t kMaxDepth = 4096;

/** A RigGeometry met on the walk, skinned once every bone is known. */
struct PendingRig
{
    const osgAnimation::RigGeometry* rig = nullptr;
    int meshNode = -1;
    int skeletonNode = -1;
    std::string place;
};

class SceneWalker
{
public:
    SceneWalker(RiggedModel& model, std::vector<std::string>& warnings)
        : _model(model), _warnings(warnings), _geometry(model, warnings)
    {
    }

    void convert(const osg::Node& root)
    {
        std::vector<const osg::StateSet*> states;
        visit(root, -1, -1, states);
        if (_skeletons == 0) throw Refusal(describe(root), "holds no osgAnimation::Skeleton");
        if (_leftOut > 0)
            warn(std::to_string(_leftOut) + " drawables outside every osgAnimation::Skeleton are left out");
        const double height = modelHeight();
        for (const PendingRig& rig : _rigs) skin(rig);
        if (_manager) readAnimations(*_manager, _targets, kTolerance * height, levers(height), _model, _warnings);
        for (std::size_t a = 0; a < _model.animations.size(); ++a)
        {
            const std::string place = "animations[" + std::to_string(a) + "]";
            double moved = 0.0;
            if (!startAnimationAtZero(_model.animations[a], moved))
                throw Refusal(place, "its keys start at " + std::to_string(-moved) +
                                         " s, too early to move them to 0 and still tell them apart");
            if (moved > 0.0)
                warn(place + ": its keys start at " + std::to_string(-moved) + " s; they are moved to start at 0");
        }
        for (int n : makeNodeNamesUnique(_model))
            warn(describe(*sourceNodes[n]) + ": a second node of its name is called '" + _model.nodes[n].name + "'");
        makeAnimationNamesUnique(_model);
        for (std::size_t n = 0; n < _model.nodes.size(); ++n)
            if (_model.nodes[n].parent < 0) _model.sceneRoots.push_back(int(n));
    }

    std::vector<const osg::Node*> sourceNodes;

private:
    void warn(const std::string& text) { _warnings.push_back(text); }

    /** Whether the node is a Skeleton or holds one (cached: shared subgraphs are asked once). */
    bool holdsSkeleton(const osg::Node& node, std::size_t depth = 0)
    {
        const auto known = _holdsSkeleton.find(&node);
        if (known != _holdsSkeleton.end()) return known->second;
        if (depth > kMaxDepth) throw Refusal(describe(node), "lies deeper than " + std::to_string(kMaxDepth) + " nodes");
        _holdsSkeleton[&node] = false; // a cycle back to here adds nothing (the walk refuses it)
        bool holds = dynamic_cast<const osgAnimation::Skeleton*>(&node) != nullptr;
        if (const osg::Group* group = node.asGroup())
            for (unsigned c = 0; c < group->getNumChildren() && !holds; ++c)
                holds = group->getChild(c) && holdsSkeleton(*group->getChild(c), depth + 1);
        return _holdsSkeleton[&node] = holds;
    }

    void findManager(const osg::Node& node)
    {
        for (const osg::Callback* callback = node.getUpdateCallback(); callback;
             callback = callback->getNestedCallback())
            if (const auto* manager = dynamic_cast<const osgAnimation::AnimationManagerBase*>(callback))
            {
                if (!_manager) _manager = manager;
                else if (manager != _manager)
                    warn(describe(node) + ": a second animation manager; only the first one's animations are read");
            }
    }

    static const osgAnimation::UpdateMatrixTransform* stackedCallback(const osg::Node& node)
    {
        for (const osg::Callback* callback = node.getUpdateCallback(); callback;
             callback = callback->getNestedCallback())
            if (const auto* stacked = dynamic_cast<const osgAnimation::UpdateMatrixTransform*>(callback)) return stacked;
        return nullptr;
    }

    int addNode(const std::string& name, int parent, const glm::dmat4& rest, const osg::Node& source)
    {
        RiggedNode node;
        node.name = name;
        node.parent = parent;
        bool shear = false;
        const std::string problem = decomposeNodeMatrix(rest, node, shear);
        if (!problem.empty()) throw Refusal(describe(source), "its matrix " + problem);
        if (shear) warn(describe(source) + ": its matrix has shear, which is left out");
        _model.nodes.push_back(node);
        sourceNodes.push_back(&source);
        return int(_model.nodes.size()) - 1;
    }

    /** The model node of a transform, its rest matrix as osgAnimation composes it. */
    int addTransform(const osg::Transform& transform, int parent)
    {
        if (transform.getReferenceFrame() != osg::Transform::RELATIVE_RF)
            throw Refusal(describe(transform), "is in an absolute reference frame, which a joint cannot be");
        glm::dmat4 rest(1.0);
        const osgAnimation::UpdateMatrixTransform* stacked = stackedCallback(transform);
        if (stacked) rest = restStackMatrix(stacked->getStackedTransforms());
        else if (const osg::MatrixTransform* matrix = transform.asMatrixTransform()) rest = toGlm(matrix->getMatrix());
        else
        {
            osg::Matrixd local;
            transform.computeLocalToWorldMatrix(local, nullptr);
            rest = toGlm(local);
        }
        const int node = addNode(transform.getName(), parent, rest, transform);
        if (stacked) _targets.emplace(stacked->getName(), StackTarget{node, &stacked->getStackedTransforms()});
        return node;
    }

    /** parent: the model node of the nearest transform above; skeleton: the model node of the Skeleton it is in, or
      * -1; states: the state sets above, nearest first. */
    void visit(const osg::Node& node, int parent, int skeleton, std::vector<const osg::StateSet*>& states)
    {
        if (std::find(_path.begin(), _path.end(), &node) != _path.end())
            throw Refusal(describe(node), "is its own ancestor (the scene graph has a cycle)");
        if (_path.size() > kMaxDepth)
            throw Refusal(describe(node), "lies deeper than " + std::to_string(kMaxDepth) + " nodes");
        findManager(node);
        if (skeleton < 0 && !holdsSkeleton(node))
        {
            countLeftOut(node);
            return;
        }
        const osg::Node* above = _path.empty() ? nullptr : _path.back();
        if (const osg::Transform* transform = node.asTransform())
        {
            const auto* bone = dynamic_cast<const osgAnimation::Bone*>(&node);
            int boneParent = parent;
            if (bone && !dynamic_cast<const osgAnimation::Bone*>(above))
            {
                // osgAnimation places a bone whose parent is no Bone in its skeleton's space.
                if (parent != skeleton)
                    warn(describe(node) + ": the transforms between it and its Skeleton are left out, as osgAnimation "
                                          "skins it in the skeleton's space");
                boneParent = skeleton;
            }
            parent = addTransform(*transform, bone ? boneParent : parent);
            if (dynamic_cast<const osgAnimation::Skeleton*>(&node))
            {
                skeleton = parent;
                ++_skeletons;
            }
            if (bone && skeleton >= 0) _bones[skeleton].emplace(bone->getName(), parent);
        }
        states.insert(states.begin(), node.getStateSet());
        _path.push_back(&node);
        if (const osg::Drawable* drawable = node.asDrawable()) addDrawable(*drawable, parent, skeleton, states);
        else if (const osg::Group* group = node.asGroup())
            for (unsigned c = 0; c < group->getNumChildren(); ++c)
                if (group->getChild(c)) visit(*group->getChild(c), parent, skeleton, states);
        _path.pop_back();
        states.erase(states.begin());
    }

    void countLeftOut(const osg::Node& node)
    {
        if (node.asDrawable()) ++_leftOut;
        else if (const osg::Group* group = node.asGroup())
            for (unsigned c = 0; c < group->getNumChildren(); ++c)
                if (group->getChild(c) && std::find(_path.begin(), _path.end(), group->getChild(c)) == _path.end())
                {
                    _path.push_back(&node);
                    countLeftOut(*group->getChild(c));
                    _path.pop_back();
                }
    }

    void addDrawable(const osg::Drawable& drawable, int parent, int skeleton, const std::vector<const osg::StateSet*>& states)
    {
        const osg::Node* holder = _path.size() > 1 ? _path[_path.size() - 2] : &drawable;
        const std::string place = describe(drawable) + (drawable.getName().empty() ? " in " + describe(*holder) : "");
        const osg::Geometry* geometry = drawable.asGeometry();
        if (!geometry)
        {
            warn(place + ": only osg::Geometry is drawn; it is left out");
            return;
        }
        const auto* rig = dynamic_cast<const osgAnimation::RigGeometry*>(geometry);
        const osg::Geometry& source = rig && rig->getSourceGeometry() ? *rig->getSourceGeometry() : *geometry;
        RiggedMesh mesh;
        mesh.name = drawable.getName();
        mesh.primitives.push_back(_geometry.convert(source, states, place));
        const int meshIndex = int(_model.meshes.size());
        _model.meshes.push_back(std::move(mesh));
        // A node of its own under the transform above it (a geode adds no transform).
        const std::string name = !drawable.getName().empty() ? drawable.getName()
                                 : !holder->getName().empty() ? holder->getName()
                                                              : std::string("drawable");
        const int node = addNode(name, parent, glm::dmat4(1.0), drawable);
        _model.nodes[node].mesh = meshIndex;
        if (rig) _rigs.push_back(PendingRig{rig, node, skeleton, place});
    }

    /** The largest extent of the nodes' rest positions (scene units), else of the meshes' vertices, else 1. */
    double modelHeight() const
    {
        glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
        for (std::size_t n = 0; n < _model.nodes.size(); ++n)
        {
            const glm::dvec3 p(restSceneMatrix(_model, int(n))[3]);
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
        double height = std::max({high.x - low.x, high.y - low.y, high.z - low.z});
        if (!(height > 0.0))
            for (const RiggedMesh& mesh : _model.meshes)
                for (const RiggedPrimitive& primitive : mesh.primitives)
                    for (const glm::vec3& p : primitive.positions)
                    {
                        low = glm::min(low, glm::dvec3(p));
                        high = glm::max(high, glm::dvec3(p));
                    }
        height = std::max({height, high.x - low.x, high.y - low.y, high.z - low.z});
        return height > 0.0 && std::isfinite(height) ? height : 1.0;
    }

    /** Per node, how far what it carries reaches in the rest pose: the farthest node or vertex below it, at least a
      * tenth of the model's height (scene units). */
    std::vector<double> levers(double height) const
    {
        const std::size_t count = _model.nodes.size();
        std::vector<glm::dvec3> positions(count);
        for (std::size_t n = 0; n < count; ++n) positions[n] = glm::dvec3(restSceneMatrix(_model, int(n))[3]);
        std::vector<double> lever(count, 0.1 * height);
        auto reach = [&](int from, const glm::dvec3& point) {
            for (int a = from; a >= 0; a = _model.nodes[a].parent)
                lever[a] = std::max(lever[a], glm::length(point - positions[a]));
        };
        for (std::size_t n = 0; n < count; ++n)
        {
            reach(int(n), positions[n]);
            if (_model.nodes[n].mesh < 0) continue;
            const glm::dmat4 place = restSceneMatrix(_model, int(n));
            for (const RiggedPrimitive& primitive : _model.meshes[_model.nodes[n].mesh].primitives)
                for (const glm::vec3& p : primitive.positions) reach(int(n), glm::dvec3(place * glm::dvec4(glm::dvec3(p), 1.0)));
        }
        return lever;
    }

    /** The skin of a RigGeometry: its bones (those its influence map names that the skeleton has), and the skeleton
      * itself where a vertex has no weight. */
    void skin(const PendingRig& pending)
    {
        const osgAnimation::VertexInfluenceMap* influences = pending.rig->getInfluenceMap();
        if (pending.skeletonNode < 0)
        {
            warn(pending.place + ": a RigGeometry outside every Skeleton is drawn rigid");
            return;
        }
        if (!influences || influences->empty())
        {
            warn(pending.place + ": has no vertex influences; it is drawn rigid");
            return;
        }
        RiggedPrimitive& primitive = _model.meshes[_model.nodes[pending.meshNode].mesh].primitives.front();
        const std::size_t vertexCount = primitive.positions.size();
        // From the geometry's space to the skeleton's, as RigGeometry computes it once (the rest transforms between).
        const glm::dmat4 skeletonFromGeometry = glm::inverse(restSceneMatrix(_model, pending.skeletonNode)) *
                                               restSceneMatrix(_model, pending.meshNode);
        RiggedSkin skin;
        skin.name = pending.rig->getName();
        std::vector<std::vector<JointWeight>> weights(vertexCount);
        const std::map<std::string, int>& bones = _bones[pending.skeletonNode];
        for (const auto& [boneName, list] : *influences)
        {
            const auto bone = bones.find(boneName);
            if (bone == bones.end())
            {
                warn(pending.place + ": bone '" + boneName + "' of its influences is not in its Skeleton; its weights "
                                     "are left out, as osgAnimation leaves them");
                continue;
            }
            const auto& source = static_cast<const osgAnimation::Bone&>(*sourceNodes[bone->second]);
            if (skin.joints.size() >= std::numeric_limits<std::uint16_t>::max())
                throw Refusal(pending.place, "has more bones than a skin takes (65535)");
            const auto joint = std::uint16_t(skin.joints.size());
            skin.joints.push_back(bone->second);
            skin.inverseBindMatrices.push_back(toGlm(source.getInvBindMatrixInSkeletonSpace()) * skeletonFromGeometry);
            for (const osgAnimation::VertexIndexWeight& weight : list)
            {
                if (weight.first >= vertexCount)
                    throw Refusal(pending.place, "bone '" + boneName + "' weights vertex " + std::to_string(weight.first) +
                                                     " of " + std::to_string(vertexCount));
                if (!(weight.second >= 0.0f) || !std::isfinite(weight.second))
                    throw Refusal(pending.place, "bone '" + boneName + "' has a weight that is not a finite number >= 0");
                if (weight.second > 0.0f) weights[weight.first].push_back(JointWeight{joint, weight.second});
            }
        }
        // osgAnimation leaves a vertex without weights (a sum under 1e-4) where it is in the skeleton's space.
        for (std::vector<JointWeight>& list : weights)
        {
            double sum = 0.0;
            for (const JointWeight& weight : list) sum += weight.weight;
            if (sum >= 1e-4) continue;
            auto self = std::find(skin.joints.begin(), skin.joints.end(), pending.skeletonNode);
            if (self == skin.joints.end())
            {
                skin.joints.push_back(pending.skeletonNode);
                skin.inverseBindMatrices.push_back(skeletonFromGeometry);
                self = skin.joints.end() - 1;
            }
            list.assign(1, JointWeight{std::uint16_t(self - skin.joints.begin()), 1.0f});
        }
        const std::size_t cut = setInfluences(primitive, weights);
        if (cut > 0)
            warn(pending.place + ": " + std::to_string(cut) +
                 " vertices have more than eight bones; the eight largest weights are kept");
        _model.skins.push_back(std::move(skin));
        _model.nodes[pending.meshNode].skin = int(_model.skins.size()) - 1;
    }

    RiggedModel& _model;
    std::vector<std::string>& _warnings;
    GeometryConverter _geometry;
    std::vector<const osg::Node*> _path;
    std::map<const osg::Node*, bool> _holdsSkeleton;
    std::size_t _skeletons = 0;
    std::size_t _leftOut = 0;
    const osgAnimation::AnimationManagerBase* _manager = nullptr;
    std::multimap<std::string, StackTarget> _targets;
    /** Per skeleton (its model node), its bones by name: the first of a name, as osgAnimation's BoneMapVisitor. */
    std::map<int, std::map<std::string, int>> _bones;
    std::vector<PendingRig> _rigs;
};

} // namespace
} // namespace osganimation

RiggedModelRead convertOsgAnimationScene(const osg::Node& scene, const std::string& name,
                                         std::vector<const osg::Node*>* sourceNodes)
{
    RiggedModelRead result;
    try
    {
        auto model = std::make_shared<RiggedModel>();
        model->sourceFile = name;
        osganimation::SceneWalker walker(*model, result.warnings);
        walker.convert(scene);
        for (std::string& warning : result.warnings) warning = name + ": " + warning;
        if (sourceNodes) *sourceNodes = walker.sourceNodes;
        result.model = model;
    }
    catch (const osganimation::Refusal& refusal)
    {
        result.warnings.clear();
        result.error = name + ": " + refusal.what();
    }
    catch (const std::bad_alloc&)
    {
        result.warnings.clear();
        result.error = name + ": not enough memory to convert it";
    }
    return result;
}

RiggedModelRead readOsgAnimationFile(const std::string& path)
{
    osgDB::Registry* registry = osgDB::Registry::instance();
    osgDB::ReaderWriter::ReadResult read = registry->readNode(path, registry->getOptions());
    if (!read.validNode())
    {
        RiggedModelRead failed;
        const std::string message = read.message().empty() ? read.statusMessage() : read.message();
        failed.error = path + ": OSG cannot read it (" + message + ")";
        return failed;
    }
    const osg::ref_ptr<osg::Node> scene = read.getNode();
    return convertOsgAnimationScene(*scene, path);
}

namespace {

/** readRiggedModelFile() reads OSG's native files as osgAnimation scenes (the import library cannot link OSG). */
[[maybe_unused]] const bool registeredWithRiggedModelFile = [] {
    for (const char* extension : {".osgt", ".osgb", ".osgx", ".osg"})
        addRiggedModelFileReader(extension, &readOsgAnimationFile);
    return true;
}();

} // namespace

} // namespace osgActor
