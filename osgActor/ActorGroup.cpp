#include <osgActor/ActorGroup>
#include <osgActor/core/detail/WorkerPool>

#include <osg/FrameStamp>

#include <unordered_map>

namespace osgActor {

ActorGroup::ActorGroup() : _numThreads(0), _actorsStale(true), _hasActorPolicy(false)
{
    setUpdateCallback(new ActorGroupUpdateCallback);
}

ActorGroup::ActorGroup(const ActorGroup& group, const osg::CopyOp& copyop)
    : osg::Group(group, copyop), _numThreads(group._numThreads), _actorsStale(true),
      _hasActorPolicy(group._hasActorPolicy), _actorPolicy(group._actorPolicy)
{
}

void ActorGroup::setNumThreads(unsigned numThreads)
{
    if (numThreads == _numThreads) return;
    _numThreads = numThreads;
    _pool.reset();
}

void ActorGroup::setActorUpdatePolicy(const ActorNode::UpdatePolicy& policy)
{
    _actorPolicy = policy;
    _hasActorPolicy = true;
    _actorsStale = true; // collectActors() hands it to every actor
}

bool ActorGroup::setChild(unsigned i, osg::Node* node)
{
    _actorsStale = true; // osg::Group::setChild() reports neither a removal nor an insertion
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

    if (!_pool) _pool = std::make_shared<WorkerPool>(_numThreads);
    _pool->parallelFor(numActors, [this, stamp](unsigned i) { _workLeft[i] = _actors[i]->updateWithinGroup(stamp); });
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

void ActorGroupUpdateCallback::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    ActorGroup* group = dynamic_cast<ActorGroup*>(node);
    if (group) group->updateActors(nv);
    // A callback nested behind this one leads the traversal on itself, over every child.
    if (group && nv && !getNestedCallback()) group->traverseAfterActors(*nv);
    else traverse(node, nv);
}

} // namespace osgActor
