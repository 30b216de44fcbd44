#include <osgActor/SkinnedMesh>

#include "SkinnedMeshDrawState.h"
#include "SkinnedMeshGeometry.h"
#include "SkinnedMeshInstance.h"

#include <osgActor/ActorNode>

#include <osg/Notify>
#include <osg/Transform>
#include <osgUtil/CullVisitor>

#include <algorithm>

namespace osgActor {

namespace {

/** The actor an intersection (or any other) visitor is traversing when it meets a skinned mesh on this thread, for
  * accept(PrimitiveFunctor&), which is given no node path. */
thread_local const ActorNode* t_actorOfVisit = nullptr;

/** The nearest ActorNode above the end of the path; whether a transform lies between it and the mesh. */
ActorNode* findActor(const osg::NodePath& path, bool& transformBetween)
{
    transformBetween = false;
    for (auto node = path.rbegin(); node != path.rend(); ++node)
    {
        if (ActorNode* actor = dynamic_cast<ActorNode*>(*node)) return actor;
        if ((*node)->asTransform()) transformBetween = true;
    }
    return nullptr;
}

unsigned frameOf(const osg::NodeVisitor& nv)
{
    return nv.getFrameStamp() ? nv.getFrameStamp()->getFrameNumber() : nv.getTraversalNumber();
}

/** What fixed function needs to light the CPU path's output as the skinning program does: linear blend shortens the
  * skinned normals a little (SkinningJob does not renormalise them), so GL normalises them. */
const osg::StateSet* cpuSkinnedFixedFunctionState()
{
    static const osg::ref_ptr<osg::StateSet> state = [] {
        osg::ref_ptr<osg::StateSet> made = new osg::StateSet;
        made->setMode(GL_NORMALIZE, osg::StateAttribute::ON);
        return made;
    }();
    return state.get();
}

/** Pushes state sets on a cull visitor and pops them all when it goes. */
class StateSetPusher
{
public:
    explicit StateSetPusher(osgUtil::CullVisitor& cv) : _cv(cv) {}
    ~StateSetPusher()
    {
        for (unsigned i = 0; i < _pushed; ++i) _cv.popStateSet();
    }
    void push(const osg::StateSet* stateSet)
    {
        if (!stateSet) return;
        _cv.pushStateSet(stateSet);
        ++_pushed;
    }

private:
    osgUtil::CullVisitor& _cv;
    unsigned _pushed = 0;
};

} // namespace

SkinnedMesh::SkinnedMesh() : _path(GPU_SKINNING), _paletteStorage(SkinPaletteStorage::Automatic),
                             _warnedNotInModelSpace(false)
{
    // The update traversal must reach the mesh each frame (it has no update callback of its own).
    setNumChildrenRequiringUpdateTraversal(1);
    setUp();
}

SkinnedMesh::SkinnedMesh(SkinPtr skin, osg::Geometry* surface) : SkinnedMesh()
{
    _skin = std::move(skin);
    _surface = surface;
    setUp();
}

SkinnedMesh::SkinnedMesh(const SkinnedMesh& mesh, const osg::CopyOp& copyop)
    : osg::Drawable(mesh, copyop), _skin(mesh._skin),
      _surface(static_cast<osg::Geometry*>(copyop(static_cast<const osg::Drawable*>(mesh._surface.get())))),
      _path(mesh._path), _paletteStorage(mesh._paletteStorage), _setupError(mesh._setupError),
      _programKey(mesh._programKey), _warnedNotInModelSpace(false)
{
    setNumChildrenRequiringUpdateTraversal(1);
    if (_surface != mesh._surface)
    {
        setUp(); // a surface of its own: geometries of its own
        return;
    }
    // The static arrays and geometries never change once built: shared. Their boxes are the mesh's: new shells.
    for (unsigned profile = 0; profile < 2; ++profile)
    {
        if (!mesh._bindPoseGeometry[profile]) continue;
        _bindPoseGeometry[profile] = new osg::Geometry(*mesh._bindPoseGeometry[profile], osg::CopyOp::SHALLOW_COPY);
        _bindPoseGeometry[profile]->setComputeBoundingBoxCallback(new FixedBoundingBox);
    }
}

SkinnedMesh::~SkinnedMesh() = default;

void SkinnedMesh::setSkin(SkinPtr skin)
{
    _skin = std::move(skin);
    setUp();
}

void SkinnedMesh::setSurface(osg::Geometry* surface)
{
    _surface = surface;
    setUp();
}

void SkinnedMesh::setPaletteStorage(SkinPaletteStorage storage)
{
    _paletteStorage = storage;
    _programKey.palette = getEffectivePaletteStorage();
}

SkinPaletteStorage SkinnedMesh::getEffectivePaletteStorage() const
{
    if (!_skin) return SkinPaletteStorage::UniformArray;
    const unsigned rows = _skin->getNumJoints() * paletteStride(_programKey);
    const bool fits = rows <= kMaxUniformPaletteVectors;
    if (_paletteStorage == SkinPaletteStorage::TextureBuffer || !fits) return SkinPaletteStorage::TextureBuffer;
    return SkinPaletteStorage::UniformArray;
}

SkinningProgramKey SkinnedMesh::getProgramKey(SkinningProfile profile) const
{
    SkinningProgramKey key = _programKey;
    key.profile = profile;
    return key;
}

void SkinnedMesh::setUp()
{
    _setupError.clear();
    _bindPoseGeometry[0] = _bindPoseGeometry[1] = nullptr;
    {
        std::lock_guard<std::mutex> lock(_instancesMutex);
        _instances.clear();
    }
    if (!_skin) _setupError = "no skin";
    else if (!_surface) _setupError = "no surface";
    else _setupError = checkSkinnedSurface(*_skin, *_surface);
    if (_setupError.empty())
    {
        _programKey = SkinningProgramKey();
        _programKey.method = _skin->getMethod();
        _programKey.inverseTranspose = _skin->getMethod() == SkinningMethod::LinearBlend &&
                                       _skin->getNormalTransform() == NormalTransform::InverseTranspose;
        _programKey.influences = shaderInfluences(*_skin);
        _programKey.palette = getEffectivePaletteStorage();
        const SkinVertexArrays arrays = makeSkinVertexArrays(*_skin);
        for (SkinningProfile profile : {SkinningProfile::Compatibility, SkinningProfile::Core})
        {
            osg::ref_ptr<osg::Geometry>& geometry = _bindPoseGeometry[static_cast<unsigned>(profile)];
            geometry = makeBindPoseGeometry(arrays, *_surface, profile);
            // Its box is the mesh's (near and far planes are computed from it), not the bind pose's.
            geometry->setComputeBoundingBoxCallback(new FixedBoundingBox);
        }
        if (_programKey.influences == 8 && _skin->getNumJoints() > 4096)
        {
            OSG_WARN << "osgActor: skinned mesh '" << getName() << "': a skin of " << _skin->getNumJoints()
                     << " joints with more than 4 influences per vertex is skinned on the CPU (the GPU path packs two "
                        "joints of at most 4096 in one float)" << std::endl;
        }
    }
    else if (_skin && _surface)
    {
        OSG_WARN << "osgActor: skinned mesh '" << getName() << "' cannot be drawn: " << _setupError << std::endl;
    }
    dirtyBound();
}

bool SkinnedMesh::gpuCanSkin() const
{
    return !(_programKey.influences == 8 && _skin && _skin->getNumJoints() > 4096);
}

osg::Geometry* SkinnedMesh::getBindPoseGeometry(SkinningProfile profile)
{
    return _bindPoseGeometry[static_cast<unsigned>(profile)].get();
}

// --- actors ---

SkinnedMeshInstance* SkinnedMesh::findInstance(const ActorNode& actor) const
{
    std::lock_guard<std::mutex> lock(_instancesMutex);
    const auto found = _instances.find(&actor);
    return found != _instances.end() && found->second->isOf(actor) ? found->second.get() : nullptr;
}

SkinnedMeshInstance* SkinnedMesh::instanceFor(ActorNode& actor) const
{
    if (!_setupError.empty()) return nullptr;
    std::lock_guard<std::mutex> lock(_instancesMutex);
    osg::ref_ptr<SkinnedMeshInstance>& slot = _instances[&actor];
    const bool same = slot && slot->isOf(actor);
    // Kept, bound or not, until the actor's definition changes: a skin that does not fit warns once.
    if (same && slot->isFor(actor.getDefinition())) return slot->isBound(actor) ? slot.get() : nullptr;
    osg::ref_ptr<SkinnedMeshInstance> instance = new SkinnedMeshInstance(actor, *_skin);
    if (same)
    {
        instance->hasOwnPath = slot->hasOwnPath;
        instance->ownPath = slot->ownPath;
    }
    slot = instance;
    return instance->isBound(actor) ? instance.get() : nullptr;
}

void SkinnedMesh::setSkinningPath(const ActorNode& actor, SkinningPath path)
{
    SkinnedMeshInstance* instance = instanceFor(const_cast<ActorNode&>(actor));
    if (!instance) return;
    instance->hasOwnPath = true;
    instance->ownPath = path;
}

SkinnedMesh::SkinningPath SkinnedMesh::getSkinningPath(const ActorNode& actor) const
{
    const SkinnedMeshInstance* instance = findInstance(actor);
    return instance && instance->hasOwnPath ? instance->ownPath : _path;
}

SkinnedMesh::Statistics SkinnedMesh::getStatistics(const ActorNode& actor) const
{
    const SkinnedMeshInstance* instance = findInstance(actor);
    return instance ? instance->statistics : Statistics();
}

osg::BoundingBox SkinnedMesh::getSkinnedBound(const ActorNode& actor) const
{
    const SkinnedMeshInstance* instance = findInstance(actor);
    return instance ? instance->getBound() : osg::BoundingBox();
}

bool SkinnedMesh::computeSkinnedVertices(const ActorNode& actor, osg::Vec3Array& positions,
                                         osg::Vec3Array* normals) const
{
    if (!_setupError.empty()) return false;
    // A scratch instance, so that the actor's own matrices (which the cull traversal reads) stay those of its
    // last update.
    ActorNode& node = const_cast<ActorNode&>(actor);
    osg::ref_ptr<SkinnedMeshInstance> scratch = new SkinnedMeshInstance(node, *_skin);
    if (!scratch->isBound(actor)) return false;
    actor.updatePose();
    scratch->updateMatrices(*_skin, actor.getPose());
    positions.resize(_skin->getNumVertices());
    if (normals) normals->resize(_skin->hasNormals() ? _skin->getNumVertices() : 0);
    scratch->skinVertices(*_skin, positions, normals);
    return true;
}

// --- traversals ---

void SkinnedMesh::accept(osg::NodeVisitor& nv)
{
    if (!nv.validNodeMask(*this)) return;
    nv.pushOntoNodePath(this);
    bool transformBetween = false;
    ActorNode* actor = findActor(nv.getNodePath(), transformBetween);
    if (actor && transformBetween && !_warnedNotInModelSpace)
    {
        OSG_WARN << "osgActor: skinned mesh '" << getName() << "' has a transform between it and actor '"
                 << actor->getName() << "': it is drawn in the actor's model space, where the joints are" << std::endl;
        _warnedNotInModelSpace = true;
    }
    switch (nv.getVisitorType())
    {
    case osg::NodeVisitor::UPDATE_VISITOR:
        if (actor) update(nv, *actor);
        nv.apply(*this); // the user's update callback, if any
        break;
    case osg::NodeVisitor::CULL_VISITOR:
        if (actor && nv.asCullVisitor()) cull(*nv.asCullVisitor(), *actor);
        break;
    default:
    {
        const ActorNode* outer = t_actorOfVisit;
        t_actorOfVisit = actor;
        nv.apply(*this);
        t_actorOfVisit = outer;
        break;
    }
    }
    nv.popFromNodePath();
}

void SkinnedMesh::update(osg::NodeVisitor& nv, ActorNode& actor)
{
    SkinnedMeshInstance* instance = instanceFor(actor);
    if (!instance) return;
    const osg::FrameStamp* stamp = nv.getFrameStamp();
    // A change of bound the actor's worker made (ActorGroup) is reported here, on the update thread: dirtying it
    // walks the parents the actors share.
    bool boundChanged = instance->takeBoundChange();
    if (!stamp || !instance->hasFollowed(stamp->getFrameNumber(), actor.getPose()))
    {
        // The pose's model matrices (the per-frame path keeps only the local ones current).
        actor.updatePose();
        const osg::BoundingBox before = instance->getBound();
        instance->updateMatrices(*_skin, actor.getPose());
        boundChanged = boundChanged || !(instance->getBound()._min == before._min &&
                                         instance->getBound()._max == before._max);
    }
    // The union is recomputed once, when the bound is next asked for (at the end of update, in a viewer).
    if (boundChanged) dirtyBound();
    if (stamp)
    {
        // From the next frame on, the actor's worker does the work above if the actor is in an ActorGroup.
        instance->setFollowedSkin(_skin);
        detail::PoseFollower::follow(actor, *instance, stamp->getFrameNumber());
    }
}

osg::BoundingBox SkinnedMesh::computeUnionBound() const
{
    osg::BoundingBox bound;
    for (auto entry = _instances.begin(); entry != _instances.end();)
    {
        if (!entry->second->isAlive())
        {
            entry = _instances.erase(entry); // the actor is gone
            continue;
        }
        if (entry->second->hasMatrices()) bound.expandBy(entry->second->getBound());
        ++entry;
    }
    for (const osg::ref_ptr<osg::Geometry>& geometry : _bindPoseGeometry)
    {
        if (!geometry) continue;
        static_cast<FixedBoundingBox*>(geometry->getComputeBoundingBoxCallback())->box = bound;
        geometry->dirtyBound();
        geometry->getBoundingBox(); // now, with the mesh's, rather than lazily in cull threads
    }
    return bound;
}

osg::BoundingBox SkinnedMesh::computeBoundingBox() const
{
    std::lock_guard<std::mutex> lock(_instancesMutex);
    const osg::BoundingBox bound = computeUnionBound();
    if (bound.valid()) return bound;
    return _skin ? toBoundingBox(_skin->getBindBox()) : osg::BoundingBox();
}

void SkinnedMesh::cull(osgUtil::CullVisitor& cv, ActorNode& actor)
{
    SkinnedMeshInstance* instance = instanceFor(actor);
    // Drawn from the actor's first update on (its matrices come from there).
    if (!instance || !instance->hasMatrices()) return;
    if (isCullingActive() && cv.isCulled(instance->getBound())) return;

    const unsigned frame = frameOf(cv);
    const SkinningProfile profile = skinningProfileOf(cv.getState());
    const SkinningPath chosen = instance->hasOwnPath ? instance->ownPath : _path;
    const SkinningPath path = gpuCanSkin() ? chosen : CPU_SKINNING;
    StateSetPusher states(cv);
    states.push(getStateSet());
    osg::Geometry* geometry = nullptr;
    if (path == GPU_SKINNING)
    {
        SkinningProgramKey key = getProgramKey(profile);
        applyDrawState(cv.getCurrentStateGraph(), key); // lit and shaded as a rigid mesh would be here
        states.push(getSkinningProgramStateSet(key));
        states.push(instance->preparePalette(frame, key, *_skin));
        geometry = getBindPoseGeometry(profile);
    }
    else
    {
        if (profile == SkinningProfile::Core)
        {
            SkinningProgramKey key;
            key.profile = profile;
            key.skinning = false;
            states.push(getSkinningProgramStateSet(key));
        }
        else
        {
            states.push(cpuSkinnedFixedFunctionState());
        }
        geometry = instance->prepareSkinnedGeometry(frame, *_skin,
                                                    *getBindPoseGeometry(SkinningProfile::Compatibility));
    }
    cv.pushOntoNodePath(geometry);
    cv.apply(*geometry);
    cv.popFromNodePath();
}

// --- functors ---

void SkinnedMesh::accept(osg::PrimitiveFunctor& functor) const
{
    if (!_setupError.empty()) return;
    const ActorNode* actor = t_actorOfVisit;
    if (!actor)
    {
        // Called outside a traversal: the one actor that draws the mesh, if there is only one.
        std::lock_guard<std::mutex> lock(_instancesMutex);
        unsigned alive = 0;
        for (const auto& entry : _instances)
            if (entry.second->isAlive()) ++alive, actor = entry.second->getActor();
        if (alive != 1) actor = nullptr;
    }
    osg::ref_ptr<osg::Vec3Array> positions = new osg::Vec3Array;
    if (!actor || !computeSkinnedVertices(*actor, *positions))
        positions = static_cast<osg::Vec3Array*>(_bindPoseGeometry[0]->getVertexArray());
    if (positions->empty()) return;
    functor.setVertexArray(positions->size(), &positions->front());
    for (unsigned i = 0; i < _surface->getNumPrimitiveSets(); ++i) _surface->getPrimitiveSet(i)->accept(functor);
}

void SkinnedMesh::accept(osg::PrimitiveIndexFunctor& functor) const
{
    if (!_setupError.empty()) return;
    functor.setVertexArray(_skin->getNumVertices(),
                           &static_cast<const osg::Vec3Array*>(_bindPoseGeometry[0]->getVertexArray())->front());
    for (unsigned i = 0; i < _surface->getNumPrimitiveSets(); ++i) _surface->getPrimitiveSet(i)->accept(functor);
}

// --- GL objects ---

void SkinnedMesh::resizeGLObjectBuffers(unsigned int maxSize)
{
    osg::Drawable::resizeGLObjectBuffers(maxSize);
    for (const osg::ref_ptr<osg::Geometry>& geometry : _bindPoseGeometry)
        if (geometry) geometry->resizeGLObjectBuffers(maxSize);
    {
        std::lock_guard<std::mutex> lock(_instancesMutex);
        for (const auto& entry : _instances) entry.second->resizeGLObjectBuffers(maxSize);
    }
    resizeSkinningProgramsGLObjectBuffers(maxSize);
}

void SkinnedMesh::releaseGLObjects(osg::State* state) const
{
    osg::Drawable::releaseGLObjects(state);
    for (const osg::ref_ptr<osg::Geometry>& geometry : _bindPoseGeometry)
        if (geometry) geometry->releaseGLObjects(state);
    {
        std::lock_guard<std::mutex> lock(_instancesMutex);
        for (const auto& entry : _instances) entry.second->releaseGLObjects(state);
    }
    releaseSkinningProgramsGLObjects(state);
}

// --- helpers ---

std::vector<SkinnedMesh*> findSkinnedMeshes(osg::Node& node)
{
    struct Finder : osg::NodeVisitor
    {
        Finder() : osg::NodeVisitor(TRAVERSE_ALL_CHILDREN) {}
        void apply(osg::Drawable& drawable) override
        {
            SkinnedMesh* mesh = dynamic_cast<SkinnedMesh*>(&drawable);
            if (mesh && std::find(meshes.begin(), meshes.end(), mesh) == meshes.end()) meshes.push_back(mesh);
        }
        std::vector<SkinnedMesh*> meshes;
    } finder;
    node.accept(finder);
    return finder.meshes;
}

void setSkinningPath(ActorNode& actor, SkinnedMesh::SkinningPath path)
{
    for (SkinnedMesh* mesh : findSkinnedMeshes(actor)) mesh->setSkinningPath(actor, path);
}

} // namespace osgActor
