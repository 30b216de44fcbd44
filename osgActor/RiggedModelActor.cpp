#include <osgActor/RiggedModelActor>

#include <osgActor/GlmOsg>
#include <osgActor/RiggedGeometry>
#include <osgActor/StickFigure>
#include <osgActor/core/SamplingJob>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/import/RiggedModelFile>

#include <osg/Geode>
#include <osg/MatrixTransform>
#include <osg/Notify>

#include <map>
#include <sstream>

namespace osgActor {

namespace {

/** One state set per material, made as the meshes ask for them. */
class MaterialStates
{
public:
    explicit MaterialStates(const RiggedModel& model) : _model(model) {}
    osg::StateSet* of(int material)
    {
        osg::ref_ptr<osg::StateSet>& state = _states[material];
        if (!state) state = createMaterialStateSet(_model, material);
        return state.get();
    }

private:
    const RiggedModel& _model;
    std::map<int, osg::ref_ptr<osg::StateSet>> _states;
};

/** Hangs every rigid primitive under the skeleton node of its joint, placed by the binding's matrix. */
void addRigidMeshes(ActorNode& actor, const RiggedActor& rigged, MaterialStates& states)
{
    for (const RigidBinding& binding : rigged.rigidMeshes)
    {
        const RiggedPrimitive& primitive = rigged.model->meshes[binding.mesh].primitives[binding.primitive];
        osg::ref_ptr<osg::Geometry> geometry = createPrimitiveGeometry(*rigged.model, primitive);
        geometry->setStateSet(states.of(primitive.material));
        osg::ref_ptr<osg::Geode> geode = new osg::Geode;
        geode->setName(primitive.place);
        geode->addDrawable(geometry.get());
        osg::ref_ptr<osg::MatrixTransform> placement = new osg::MatrixTransform(toOsg(binding.jointFromMesh));
        placement->addChild(geode.get());
        if (binding.jointFromMesh != glm::dmat4(1.0))
            placement->getOrCreateStateSet()->setMode(GL_NORMALIZE, osg::StateAttribute::ON);
        actor.getSkeletonNode(binding.joint)->addChild(placement.get());
    }
}

/** A Geode named "skins" holding a SkinnedMesh per skinned primitive, skinned where path says; null when the model
  * has no skin. Its drawables go below an actor, in its model space. */
osg::ref_ptr<osg::Geode> createSkinsGeode(const RiggedActor& rigged, MaterialStates& states,
                                          SkinnedMesh::SkinningPath path)
{
    if (rigged.skins.empty()) return nullptr;
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->setName("skins");
    for (const SkinnedPrimitive& skinned : rigged.skins)
    {
        osg::ref_ptr<SkinnedMesh> mesh = createSkinnedMesh(*rigged.model, skinned);
        mesh->setSkinningPath(path);
        mesh->setStateSet(states.of(rigged.model->meshes[skinned.mesh].primitives[skinned.primitive].material));
        geode->addDrawable(mesh.get());
    }
    return geode;
}

/** The clip of that name, or the first; null when there is none of that name. */
ClipPtr chooseClip(const RiggedActor& rigged, const std::string& name)
{
    if (name.empty()) return rigged.clips.empty() ? ClipPtr() : rigged.clips.front();
    for (const ClipPtr& clip : rigged.clips)
        if (clip->getName() == name) return clip;
    return ClipPtr();
}

} // namespace

const char* const kSkinsNodeDescriptionPrefix = "osgActor:skins ";

std::string getSkinsNodeFile(const osg::Node& node)
{
    const std::string prefix = kSkinsNodeDescriptionPrefix;
    for (const std::string& text : node.getDescriptions())
        if (text.compare(0, prefix.size(), prefix) == 0) return text.substr(prefix.size());
    return std::string();
}

osg::ref_ptr<osg::Geode> readRiggedModelSkins(const std::string& path, const std::string& fileName,
                                              const ActorDefinition& definition, std::string& error)
{
    const RiggedModelRead read = readRiggedModelFile(path);
    if (!read)
    {
        error = read.error;
        return nullptr;
    }
    // The options readRiggedModelActor() builds with by default: the skins' inverse bind matrices depend on where
    // the root scale goes (not on the up axis, which turns the definition's roots only).
    const RiggedActor rigged = buildRiggedActor(read.model, RiggedActorOptions());
    if (!rigged)
    {
        error = rigged.error;
        return nullptr;
    }
    if (rigged.skins.empty())
    {
        error = path + ": the file has no skinned mesh";
        return nullptr;
    }
    for (const SkinnedPrimitive& skinned : rigged.skins)
    {
        const SkinBinding binding = bindSkinToDefinition(*skinned.skin, definition);
        if (!binding)
        {
            error = path + ": " + binding.error;
            return nullptr;
        }
    }
    for (const std::string& warning : read.warnings) OSG_WARN << "osgActor: " << warning << std::endl;
    for (const std::string& warning : rigged.warnings) OSG_WARN << "osgActor: " << warning << std::endl;
    MaterialStates states(*rigged.model);
    osg::ref_ptr<osg::Geode> geode = createSkinsGeode(rigged, states, SkinnedMesh::GPU_SKINNING);
    geode->addDescription(kSkinsNodeDescriptionPrefix + fileName);
    return geode;
}

bool parseRiggedModelOptionString(const std::string& text, RiggedModelActorOptions& options, std::string& error)
{
    std::istringstream words(text);
    std::string word;
    while (words >> word)
    {
        const std::size_t equals = word.find('=');
        const std::string key = word.substr(0, equals);
        const std::string value = equals == std::string::npos ? std::string() : word.substr(equals + 1);
        auto bad = [&](const char* expected) {
            error = "option " + key + " must be " + expected + ", not '" + value + "'";
            return false;
        };
        if (key == "clip" && equals != std::string::npos) options.clip = value;
        else if (key == "mode" && equals != std::string::npos)
        {
            if (!parsePlayMode(value, options.playMode)) return bad("loop, once or pingpong");
        }
        else if (key == "rootScale" && equals != std::string::npos)
        {
            if (value == "above") options.rootScale = RootScale::AboveActor;
            else if (value == "lengths") options.rootScale = RootScale::InLengths;
            else return bad("above or lengths");
        }
        else if (key == "skinning" && equals != std::string::npos)
        {
            if (value == "gpu") options.skinning = SkinnedMesh::GPU_SKINNING;
            else if (value == "cpu") options.skinning = SkinnedMesh::CPU_SKINNING;
            else return bad("gpu or cpu");
        }
        else if (word == "figure") options.addFigure = true;
        else if (word == "noFigure") options.addFigure = false;
        else if (word == "yUp") options.zUp = false;
        // anything else belongs to another plugin
    }
    return true;
}

RiggedModelActor readRiggedModelActor(const std::string& path, const RiggedModelActorOptions& options,
                                      std::string& error)
{
    RiggedModelActor result;
    const RiggedModelRead read = readRiggedModelFile(path);
    if (!read)
    {
        error = read.error;
        return result;
    }
    RiggedActorOptions mapping;
    mapping.rootScale = options.rootScale;
    mapping.zUp = options.zUp;
    RiggedActor rigged = buildRiggedActor(read.model, mapping);
    if (!rigged)
    {
        error = rigged.error;
        return result;
    }
    const ClipPtr clip = chooseClip(rigged, options.clip);
    if (!options.clip.empty() && !clip)
    {
        error = path + ": no animation named '" + options.clip + "'";
        return result;
    }
    for (const std::string& warning : read.warnings) OSG_WARN << "osgActor: " << warning << std::endl;
    for (const std::string& warning : rigged.warnings) OSG_WARN << "osgActor: " << warning << std::endl;

    osg::ref_ptr<ActorNode> actor = new ActorNode(rigged.definition);
    actor->setName(rigged.definition->getName());
    ClipLibraryPtr library = std::make_shared<ClipLibrary>();
    for (const ClipPtr& each : rigged.clips) library->addClip(each);
    actor->setClipLibrary(library);
    if (clip)
    {
        auto player = std::make_shared<ClipPlayer>(clip);
        player->setName("clip");
        player->setPlayMode(options.playMode);
        actor->addController(player);
        // Pose the clip's start at once, so bounds and queries are right before the first update.
        std::vector<double> values(clip->getNumChannels());
        ClipCursor cursor;
        clip->initCursor(cursor);
        sampleEveryChannel(*clip, 0.0, cursor, values);
        std::vector<double> dofs = rigged.definition->getDefaultDofs();
        for (unsigned c = 0; c < clip->getNumChannels(); ++c)
            dofs[rigged.definition->findDof(clip->getChannel(c).target)] = values[c];
        actor->setDofs(dofs);
        actor->updatePose();
    }
    MaterialStates states(*rigged.model);
    addRigidMeshes(*actor, rigged, states);
    const osg::ref_ptr<osg::Geode> skins = createSkinsGeode(rigged, states, options.skinning);
    if (skins.valid())
    {
        if (options.rootScale == RootScale::AboveActor) skins->addDescription(kSkinsNodeDescriptionPrefix + path);
        for (unsigned i = 0; i < skins->getNumDrawables(); ++i)
            result.skinnedMeshes.push_back(static_cast<SkinnedMesh*>(skins->getDrawable(i)));
        actor->addChild(skins.get());
    }
    if (options.addFigure) addStickFigure(*actor);

    result.actor = actor;
    result.sceneNode = actor;
    if (rigged.rootScale != 1.0)
    {
        osg::ref_ptr<osg::MatrixTransform> above = new osg::MatrixTransform(osg::Matrixd::scale(
            rigged.rootScale, rigged.rootScale, rigged.rootScale));
        above->setName(actor->getName() + " scale");
        above->getOrCreateStateSet()->setMode(GL_RESCALE_NORMAL, osg::StateAttribute::ON);
        above->addChild(actor.get());
        result.sceneNode = above;
    }
    result.rigged = std::move(rigged);
    return result;
}

} // namespace osgActor
