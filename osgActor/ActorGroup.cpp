#include <osgActor/ActorGroup>

#include <osg/FrameStamp>

namespace osgActor {

ActorGroup::ActorGroup() : _numThreads(0)
{
    setUpdateCallback(new ActorGroupUpdateCallback);
}

ActorGroup::ActorGroup(const ActorGroup& group, const osg::CopyOp& copyop)
    : osg::Group(group, copyop), _numThreads(group._numThreads)
{
}

void ActorGroup::setNumThreads(unsigned numThreads)
{
    if (numThreads == _numThreads) return;
    _numThreads = numThreads;
    _pool.reset();
}

void ActorGroup::updateActors(const osg::NodeVisitor* nv)
{
    const osg::FrameStamp* stamp = nv ? nv->getFrameStamp() : nullptr;
    _claimed.clear();
    for (unsigned i = 0; i < getNumChildren(); ++i)
    {
        ActorNode* actor = dynamic_cast<ActorNode*>(getChild(i));
        if (actor && actor->claimFrame(stamp)) _claimed.push_back(actor);
    }
    if (_claimed.empty()) return;
    const double time = stamp ? stamp->getSimulationTime() : ActorNode::kNoTime;

    if (!_pool) _pool = std::make_shared<WorkerPool>(_numThreads);
    _pool->parallelFor(static_cast<unsigned>(_claimed.size()), [this, time](unsigned i) {
        _claimed[i]->computeFrame(time);
        _claimed[i]->writeJointMatrices();
    });
    for (ActorNode* actor : _claimed) actor->writeActorMatrix();
}

void ActorGroupUpdateCallback::operator()(osg::Node* node, osg::NodeVisitor* nv)
{
    if (ActorGroup* group = dynamic_cast<ActorGroup*>(node)) group->updateActors(nv);
    traverse(node, nv);
}

} // namespace osgActor
