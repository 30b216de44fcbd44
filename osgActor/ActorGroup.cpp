#include <osgActor/ActorGroup>
#include <osgActor/core/detail/WorkerPool>
#include <osgActor/detail/ActorCull.h>
#include <osgActor/detail/OwnBounds.h>

#include <OpenThreads/Thread>
#include <osg/FrameStamp>
#include <osgUtil/CullVisitor>

#include <typeinfo>
#include <unordered_map>

namespace osgActor {

namespace {

/** Where the cull's preparation on the threads starts to pay (docs/performance.md). */
constexpr unsigned kDefaultMinActorsForParallelCull = 64;

/** Puts the calling worker on the processors asked for, or on every processor for an empty set. */
void applyWorkerAffinity(const OpenThreads::Affinity& asked)
{
    OpenThreads::Affinity affinity = asked;
    if (!affinity)
        for (int cpu = 0; cpu < OpenThreads::GetNumberOfProcessors(); ++cpu) affinity.add(static_cast<unsigned>(cpu));
    OpenThreads::SetProcessorAffinityOfCurrentThread(affinity);
}

} // namespace

ActorGroup::ActorGroup()
    : _numThreads(0), _minActorsForParallelCull(kDefaultMinActorsForParallelCull), _numParallelCulls(0),
      _actorsStale(true), _childrenVersion(0), _hasActorPolicy(false)
{
    _culling.clear();
    setUpdateCallback(new ActorGroupUpdateCallback);
}

ActorGroup::ActorGroup(const ActorGroup& group, const osg::CopyOp& copyop)
    : osg::Group(group, copyop), _numThreads(group._numThreads), _workerAffinity(group._workerAffinity),
      _minActorsForParallelCull(group._minActorsForParallelCull), _numParallelCulls(0), _actorsStale(true),
      _childrenVersion(0), _hasActorPolicy(group._hasActorPolicy), _actorPolicy(group._actorPolicy)
{
    _culling.clear();
}

void ActorGroup::setNumThreads(unsigned numThreads)
{
    if (numThreads == _numThreads) return;
    std::lock_guard<std::mutex> lock(_poolMutex);
    _numThreads = numThreads;
    _pool.reset();
}

void ActorGroup::setWorkerAffinity(const OpenThreads::Affinity& affinity)
{
    std::lock_guard<std::mutex> lock(_poolMutex);
    _workerAffinity = affinity;
    _pool.reset(); // the next frame's workers start on the new processors
}

void ActorGroup::setActorUpdatePolicy(const ActorNode::UpdatePolicy& policy)
{
    _actorPolicy = policy;
    _hasActorPolicy = true;
    _actorsStale = true; // collectActors() hands it to every actor
}

bool ActorGroup::setChild(unsigned i, osg::Node* node)
{
    childrenChanged(); // osg::Group::setChild() reports neither a removal nor an insertion
    return osg::Group::setChild(i, node);
}

void ActorGroup::collectActors()
{
    _actors.clear();
    _actorOfChild.assign(_children.size(), -1);
    std::unordered_map<ActorNode*, int> indexOf;
    for (std::size_t i = 0; i < _children.size(); ++i)
    {
        ActorNode* actor = dynamic_cast<ActorNode*>(_children[i].get());
        if (!actor) continue;
        // An actor that is a child twice is updated once (two workers must never run the same actor).
        auto found = indexOf.emplace(actor, static_cast<int>(_actors.size()));
        if (found.second) _actors.push_back(actor);
        if (found.second && _hasActorPolicy) actor->setUpdatePolicy(_actorPolicy);
        _actorOfChild[i] = found.first->second;
    }
    _actorsStale = false;
}

void ActorGroup::updateActors(const osg::NodeVisitor* nv)
{
    if (_actorsStale) collectActors();
    const unsigned numActors = static_cast<unsigned>(_actors.size());
    _workLeft.assign(numActors, ActorNode::GROUP_WORK_NONE);
    if (numActors == 0) return;
    const osg::FrameStamp* stamp = nv ? nv->getFrameStamp() : nullptr;

    {
        // Waits for a camera still culling on its own thread (a model without an end-of-cull barrier).
        std::lock_guard<std::mutex> lock(_poolMutex);
        pool().parallelFor(numActors,
                           [this, stamp](unsigned i) { _workLeft[i] = _actors[i]->updateWithinGroup(stamp); });
    }
    // In child order, as the serial update would: bound dirtying walks shared parents.
    for (unsigned i = 0; i < numActors; ++i)
        if (_workLeft[i] & ActorNode::GROUP_WORK_WRITE_ACTOR_MATRIX) _actors[i]->writeActorMatrix();
}

void ActorGroup::traverseAfterActors(osg::NodeVisitor& nv)
{
    for (std::size_t i = 0; i < _children.size(); ++i)
    {
        // Skipped only while the lists still describe the children (a callback may change them as we go).
        const bool listed = !_actorsStale && i < _actorOfChild.size() && _workLeft.size() == _actors.size();
        const int actor = listed ? _actorOfChild[i] : -1;
        if (actor >= 0 && !(_workLeft[actor] & ActorNode::GROUP_WORK_VISIT)) continue;
        _children[i]->accept(nv);
    }
}

WorkerPool& ActorGroup::pool()
{
    if (!_pool)
    {
        const OpenThreads::Affinity affinity = _workerAffinity;
        _pool = std::make_shared<WorkerPool>(_numThreads, [affinity] { applyWorkerAffinity(affinity); });
    }
    return *_pool;
}

void ActorGroup::traverse(osg::NodeVisitor& nv)
{
    osgUtil::CullVisitor* cv = nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR ? nv.asCullVisitor() : nullptr;
    if (!cv || !cullActorsInParallel(*cv)) osg::Group::traverse(nv);
}

osg::BoundingSphere ActorGroup::computeBound() const
{
    const unsigned numChildren = getNumChildren();
    if (numChildren >= _minActorsForParallelCull && numChildren > 0)
    {
        // The threads as a cull takes them: not while the update or another camera's cull has them, nor within a
        // cull of this group (its traversal asks bounds below).
        ActorGroup& group = const_cast<ActorGroup&>(*this);
        CullThreads threads(group);
        if (WorkerPool* workers = threads.get())
            workers->parallelFor(numChildren, [&group](unsigned i) {
                osg::Node& child = *group._children[i];
                if (typeid(child) == typeid(ActorNode)) detail::computeOwnBound(static_cast<ActorNode&>(child));
            });
    }
    return osg::Group::computeBound();
}

ActorGroup::CullThreads::CullThreads(ActorGroup& group) : _group(group), _flagTaken(false), _pool(nullptr)
{
    // Another camera's cull (on another thread, or within this one's traversal), or the next frame's update.
    if (_group._culling.test_and_set(std::memory_order_acquire)) return;
    _flagTaken = true;
    _lock = std::unique_lock<std::mutex>(_group._poolMutex, std::try_to_lock);
    if (!_lock.owns_lock()) return;
    WorkerPool& workers = _group.pool();
    if (workers.getNumThreads() >= 2) _pool = &workers;
}

ActorGroup::CullThreads::~CullThreads()
{
    if (_lock.owns_lock()) _lock.unlock();
    if (_flagTaken) _group._culling.clear(std::memory_order_release);
}

bool ActorGroup::cullActorsInParallel(osgUtil::CullVisitor& cv)
{
    if (_children.size() < _minActorsForParallelCull || !detail::ActorCull::canCullAsOne(cv)) return false;
    CullThreads threads(*this);
    if (!threads.get()) return false;
    WorkerPool& workers = *threads.get();
    _cullActors.clear();
    for (const osg::ref_ptr<osg::Node>& child : _children)
        if (ActorNode* actor = dynamic_cast<ActorNode*>(child.get())) _cullActors.push_back(actor);
    const unsigned numActors = static_cast<unsigned>(_cullActors.size());
    if (numActors < _minActorsForParallelCull) return false;

    // Bounds are computed lazily, and a bound below an actor (a geode, a skinned mesh) may be shared by many:
    // computed here, on this thread, all at once, so that the threads only read them.
    getBound();
    const detail::ActorCullView view(cv);
    const osg::Matrixd& modelView = *cv.getModelViewMatrix();
    const osg::CullingSet& cullingSet = cv.getCurrentCullingSet();
    _cullPrepared.assign(numActors, 0);
    workers.parallelFor(numActors, [&](unsigned i) {
        _cullPrepared[i] = _cullActors[i]->prepareCullWithinGroup(view, modelView, cullingSet, &cv);
    });
    // The visitor's own traversal, child by child: each prepared actor makes its calls from its preparation.
    osg::Group::traverse(cv);
    for (unsigned i = 0; i < numActors; ++i)
        if (_cullPrepared[i]) _cullActors[i]->releaseCullWithinGroup(&cv);
    _numParallelCulls.fetch_add(1, std::memory_order_relaxed);
    return true;
}

void ActorGroupUpdateCallback::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    ActorGroup* group = dynamic_cast<ActorGroup*>(node);
    if (group) group->updateActors(nv);
    // A callback nested behind this one leads the traversal on itself, over every child.
    if (group && nv && !getNestedCallback()) group->traverseAfterActors(*nv);
    else traverse(node, nv);
}

} // namespace osgActor
