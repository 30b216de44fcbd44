#include <osgActor/core/ActorPose>
#include <osgActor/core/ForwardKinematicsJob>

#include <algorithm>
#include <cmath>

namespace osgActor {

namespace {

/** The FK job's trigonometry scratch for a pose of numDofs DOFs: one buffer per thread, grown as needed, so it stays
  * in cache from one actor to the next instead of each pose carrying its own. */
double* trigScratch(unsigned numDofs)
{
    thread_local std::vector<double> scratch;
    const std::size_t needed = std::size_t(ForwardKinematicsJob::kTrigScratchPerDof) * numDofs;
    if (scratch.size() < needed) scratch.resize(needed);
    return scratch.data();
}

} // namespace

ActorPose::ActorPose(ActorDefinitionPtr definition) : _definition(std::move(definition))
{
    if (!_definition) return;
    const unsigned numJoints = _definition->getNumJoints();
    _dofs = _definition->getDefaultDofs();
    _dofMins = _definition->getDofRangeMins().data();
    _dofMaxs = _definition->getDofRangeMaxs().data();
    _dofJoints = _definition->getDofJoints().data();
    _jointDirty.assign(numJoints, 1);
    _localChanged.assign(numJoints, 0);
    _modelChanged.assign(numJoints, 0);
    _modelStale.assign(numJoints, 0);
    _local = LocalMatrices(numJoints);
    _model.assign(numJoints, glm::dmat4(1.0));
    _anyDirty = numJoints > 0;
}

DofWriteStatus ActorPose::setDofs(const double* values, std::size_t count)
{
    if (count != _dofs.size()) return DofWriteStatus::SizeMismatch;
    if (!std::all_of(values, values + count, [](double v) { return std::isfinite(v); }))
        return DofWriteStatus::NotFinite;
    bool anyClamped = false;
    for (unsigned i = 0; i < count; ++i)
        anyClamped = setDof(i, values[i]) == DofWriteStatus::Clamped || anyClamped;
    return anyClamped ? DofWriteStatus::Clamped : DofWriteStatus::Written;
}

void ActorPose::resetDofs()
{
    if (_definition) setDofs(_definition->getDefaultDofs().data(), _definition->getNumDofs());
}

void ActorPose::markAllJointsDirty()
{
    std::fill(_jointDirty.begin(), _jointDirty.end(), 1);
    _anyDirty = !_jointDirty.empty();
}

unsigned ActorPose::updateMatrices() { return runForwardKinematics(true, true); }

unsigned ActorPose::updateLocalMatrices() { return runForwardKinematics(true, false); }

void ActorPose::updateModelMatrices() { runForwardKinematics(false, true); }

unsigned ActorPose::runForwardKinematics(bool rebuildLocal, bool computeModel)
{
    const bool localWork = rebuildLocal && _anyDirty;
    const bool modelWork = computeModel && (_anyModelStale || localWork);
    if (!localWork && !modelWork) return 0;
    ForwardKinematicsJob job;
    job.definition = _definition.get();
    job.dofs = _dofs.data();
    job.jointDirty = _jointDirty.data();
    job.local = _local.targets();
    job.model = _model.data();
    job.localChanged = _localChanged.data();
    job.modelStale = _modelStale.data();
    job.modelChanged = _modelChanged.data();
    job.trigScratch = trigScratch(getNumDofs());
    job.computeModel = computeModel;
    job.rebuildLocal = rebuildLocal;
    job.run();
    if (rebuildLocal) _anyDirty = false;
    _anyModelStale = !computeModel && (_anyModelStale || job.numRecomputed > 0);
    _anyLocalChanged = _anyLocalChanged || job.numRecomputed > 0;
    _totalRecomputed += job.numRecomputed;
    return job.numRecomputed;
}

} // namespace osgActor
