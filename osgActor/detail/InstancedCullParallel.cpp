// Internal to the library (not installed, NOT API): the instanced cull's actors on an ActorGroup's threads
// (InstancedCull::cullInParallel()), with the same render graph, texels and statistics as the cull on one thread.
//
// The serial cull adds each actor's instances to its batches as it goes, in child order: a batch's instance goes to
// its region of the frame's buffer while the region has room, to the batch's overflow after, and a batch that
// overflowed is moved whole past every region once every actor is culled (gatherOverflow()). Here a first pass culls
// each actor on a thread into that thread's scratch (its instances' data, in runs of one batch); the cull thread then
// goes through the children in order (the ordinary traversals, the other children, the actors a worker may not decide,
// the near and far merged, and, from the runs, each run's place among its batch's instances: the count so far); a
// last pass writes each run at its place, in the region where the serial cull would have found room for it, and, for
// a batch that outgrew its region, also where the batch moves (the layout gatherOverflow() makes, found from the
// counts before the pass).
#include <osgActor/detail/InstancedCull.h>

#include <osgActor/ActorNode>
#include <osgActor/core/detail/WorkerPool>
#include <osgActor/detail/InstancedSkin.h>

#include <algorithm>
#include <cstring>
#include <typeinfo>
#include <unordered_set>
#include <utility>

namespace osgActor {
namespace detail {

bool InstancedCull::cullInParallel(osg::Group& group, const Threads& threads)
{
    listActorChildren(group, threads.childrenVersion);
    const std::vector<unsigned>& actorChildren = _state._actorChildren;
    const unsigned numActors = static_cast<unsigned>(actorChildren.size());
    // An actor that is a child twice is culled twice, one cull after the other: never on two threads at once.
    if (_state._childrenRepeat || numActors < std::max(threads.minActors, 1u)) return false;
    WorkerPool& workers = *threads.pool;
    if (_state._scratch.size() < workers.getNumThreads()) _state._scratch.resize(workers.getNumThreads());
    _scratch = &_state._scratch[0];
    for (InstancedCullState::ActorScratch& scratch : _state._scratch)
    {
        scratch.stateVerdicts.clear();
        scratch.skinStateVerdicts.clear();
        scratch.runs.clear();
        scratch.data.clear();
        scratch.seenModelViews.clear();
        scratch.subtreeVisits.clear();
        scratch.wrote = false;
    }
    // Bounds are computed lazily, and one below an actor (a geode, a drawable) may be shared by many: computed here,
    // all at once, so that the threads only read them (as ActorGroup's cull does).
    group.getBound();
    prepareSkinnedBatches();

    std::vector<ActorOutcome>& outcomes = _state._outcomes;
    outcomes.resize(numActors);
    workers.parallelForWithThread(numActors, [&](unsigned i, unsigned thread) {
        InstancedCull worker(*this, thread);
        ActorNode& actor = static_cast<ActorNode&>(*group.getChild(actorChildren[i]));
        // The thread's next actors fetched ahead, as the serial cull fetches the next children. Where the look-ahead
        // holds an actor's state while another thread comes to cull it (at the end of a thread's share), that actor
        // is DEFERRED: culled on this thread after, as the serial cull would.
        for (unsigned ahead = 1; ahead <= ActorNode::kCullLookahead && i + ahead < numActors; ++ahead)
        {
            const osg::Node& next = *group.getChild(actorChildren[i + ahead]);
            actor.prefetchCullAhead(next, ahead);
            worker.prefetchKeptAhead(next, ahead);
        }
        worker.cullChildInto(actor, outcomes[i]);
    });

    // In child order: what the visitor is told, and each run's place among its batch's instances.
    InstancedCullState::Statistics& statistics = _state._statistics;
    std::vector<InstancedCullState::Batch>& batches = _state._batches;
    const unsigned numChildren = group.getNumChildren();
    for (unsigned i = 0, a = 0; i < numChildren; ++i)
    {
        osg::Node& child = *group.getChild(i);
        if (a == numActors || actorChildren[a] != i)
        {
            child.accept(_cv);
            continue;
        }
        ActorNode& actor = static_cast<ActorNode&>(child);
        ActorOutcome& outcome = outcomes[a++];
        if (outcome.kind == ActorOutcome::DEFERRED)
        {
            // Here, where the serial cull would: the verdicts and batches it makes are made in the same order.
            InstancedCull here(*this, 0);
            here._mayDecideShared = true;
            here.cullChildInto(actor, outcome);
        }
        switch (outcome.kind)
        {
        case ActorOutcome::OUT_OF_VIEW: ++statistics.actorsOutOfView; break;
        case ActorOutcome::ORDINARY:
            ++statistics.actorsOrdinary;
            actor.accept(_cv);
            break;
        case ActorOutcome::INSTANCED:
        case ActorOutcome::KEPT:
        {
            ++statistics.actorsInstanced;
            if (outcome.kind == ActorOutcome::KEPT) ++statistics.actorsKept;
            if (outcome.compiled) ++statistics.actorsCompiled;
            InstancedCullState::ActorScratch& scratch = _state._scratch[outcome.thread];
            if (outcome.seen != ~0u) actor.noteSeenInFrame(_cv, scratch.seenModelViews[outcome.seen]);
            if (outcome.numSubtrees) traverseSubtrees(actor, scratch, outcome.firstSubtree, outcome.numSubtrees);
            if (_computeNearFar)
            {
                outcome.skinDepths.mergeInto(_cv);
                outcome.depths.mergeInto(_cv);
            }
            if (outcome.wrote) _wroteTexels = true;
            for (unsigned k = 0; k < outcome.numRuns; ++k)
            {
                InstancedCullState::ActorRun& run = scratch.runs[outcome.firstRun + k];
                run.first = batches[run.batch].count;
                batches[run.batch].count += run.count;
            }
            break;
        }
        case ActorOutcome::DEFERRED: break; // not after the cull above, which decides
        }
    }

    // The batches that outgrew their regions, moved whole past every region in batch order, as gatherOverflow() moves
    // them.
    std::vector<unsigned>& movedBase = _state._movedBase;
    movedBase.assign(batches.size(), ~0u);
    unsigned end = 0, moved = 0;
    for (const InstancedCullState::Batch& batch : batches)
    {
        end += batch.capacity;
        if (batch.count * batch.texels > batch.capacity) moved += batch.count * batch.texels;
    }
    if (moved)
    {
        if (!_state._frame) _state._frame = acquireFrame(_textureUnit);
        _state._texels = _state._frame->growTexels(end + moved);
        _state._frame->moved();
        _wroteTexels = true;
        for (std::size_t b = 0; b < batches.size(); ++b)
        {
            if (batches[b].count * batches[b].texels <= batches[b].capacity) continue;
            movedBase[b] = end;
            end += batches[b].count * batches[b].texels;
        }
    }

    workers.parallelForWithThread(numActors, [&](unsigned i, unsigned thread) {
        writeActor(static_cast<ActorNode&>(*group.getChild(actorChildren[i])), outcomes[i],
                   _state._scratch[thread].wrote);
    });
    for (std::size_t b = 0; b < batches.size(); ++b)
        if (movedBase[b] != ~0u) batches[b].base = movedBase[b];
    for (const InstancedCullState::ActorScratch& scratch : _state._scratch)
        if (scratch.wrote) _wroteTexels = true;
    return true;
}

void InstancedCullState::InstanceData::grow(std::size_t least)
{
    // Doubled, so that a crowd's first culls reallocate it a few times, and the next ones not at all.
    const std::size_t capacity = std::max(least, 2 * _capacity);
    std::unique_ptr<float[]> floats(new float[capacity]);
    if (_size) std::memcpy(floats.get(), _floats.get(), _size * sizeof(float));
    _floats = std::move(floats);
    _capacity = capacity;
}

void InstancedCull::listActorChildren(osg::Group& group, unsigned childrenVersion)
{
    if (_state._childrenListed && _state._childrenVersion == childrenVersion) return;
    _state._actorChildren.clear();
    _state._childrenRepeat = false;
    std::unordered_set<const osg::Node*> actors;
    for (unsigned i = 0; i < group.getNumChildren(); ++i)
    {
        const osg::Node& child = *group.getChild(i);
        if (typeid(child) != typeid(ActorNode)) continue;
        _state._actorChildren.push_back(i);
        if (!actors.insert(&child).second) _state._childrenRepeat = true;
    }
    _state._childrenListed = true;
    _state._childrenVersion = childrenVersion;
}

void InstancedCull::prepareSkinnedBatches()
{
    // The serial cull finds a skinned batch's texels per instance when an actor first needs them in the cull
    // (canInstanceSkins()); here every skinned batch's, before the threads read them (a batch no actor takes keeps no
    // instance, whatever its texels). And the box of the geometry its instanced draws draw, which OSG computes lazily.
    for (InstancedCullState::Batch& batch : _state._batches)
    {
        if (!batch.mesh) continue;
        batch.texels = InstancedSkin::texelsPerInstance(*batch.mesh);
        batch.texelsKnown = true;
        if (const osg::Geometry* geometry = InstancedSkin::geometryOf(*batch.mesh, _profile))
            geometry->getBoundingBox();
    }
}

void InstancedCull::cullChildInto(ActorNode& actor, ActorOutcome& outcome)
{
    outcome.kind = ActorOutcome::DEFERRED;
    outcome.thread = static_cast<unsigned>(_scratch - _state._scratch.data());
    outcome.firstRun = static_cast<unsigned>(_scratch->runs.size());
    outcome.firstData = _scratch->data.size();
    outcome.seen = ~0u;
    outcome.firstSubtree = 0;
    outcome.numSubtrees = 0;
    outcome.compiled = false;
    outcome.skinDepths = DepthRange();
    outcome.depths = DepthRange();
    _outcome = &outcome;
    _deferred = false;
    _wroteTexels = false;
    _recording = nullptr;
    cullChild(actor);
    outcome.numRuns = static_cast<unsigned>(_scratch->runs.size()) - outcome.firstRun;
    outcome.wrote = _wroteTexels;
    _outcome = nullptr;
}

void InstancedCull::writeActor(ActorNode& actor, const ActorOutcome& outcome, bool& wrote) const
{
    if (outcome.kind != ActorOutcome::INSTANCED && outcome.kind != ActorOutcome::KEPT) return;
    const InstancedCullState::ActorScratch& scratch = _state._scratch[outcome.thread];
    const InstancedCullState::ActorRun* runs = scratch.runs.data() + outcome.firstRun;
    ActorCullState& actorState = *actor._cullState;
    if (outcome.kind == ActorOutcome::KEPT)
    {
        // As addKeptRuns(): a run where this frame's last cull added it is not written again.
        ActorCullState::InstancedVerdict& kept = actorState._instancedVerdict;
        const bool inFrame = keptInFrame(kept);
        bool samePlaces = true;
        const float* matrix = kept.matrices.data();
        for (unsigned k = 0; k < outcome.numRuns; ++k)
        {
            const unsigned at = kept.runs[k].at;
            writeRun(runs[k].batch, runs[k].first, runs[k].count, matrix, &kept.runs[k], inFrame, wrote);
            samePlaces = samePlaces && kept.runs[k].at == at;
            matrix += 16 * std::size_t(runs[k].count);
        }
        notePlaced(kept, samePlaces);
    }
    else
    {
        const float* data = scratch.data.data() + outcome.firstData;
        for (unsigned k = 0; k < outcome.numRuns; ++k)
        {
            writeRun(runs[k].batch, runs[k].first, runs[k].count, data, nullptr, false, wrote);
            data += 4 * std::size_t(_state._batches[runs[k].batch].texels) * runs[k].count;
        }
    }
    actorState.release(); // held since the first pass
}

void InstancedCull::writeRun(unsigned b, unsigned first, unsigned count, const float* data,
                             ActorCullState::InstancedVerdict::Run* kept, bool inFrame, bool& wrote) const
{
    const InstancedCullState::Batch& batch = _state._batches[b];
    float* texels = _state._texels;
    const std::size_t floats = 4 * std::size_t(batch.texels);
    if ((first + count) * batch.texels <= batch.capacity)
    {
        // The serial cull's room in the region for the whole run (roomInRegion()).
        const unsigned at = batch.base + first * batch.texels;
        if (!kept || !inFrame || kept->at != at)
        {
            std::memcpy(texels + 4 * std::size_t(at), data, floats * count * sizeof(float));
            wrote = true;
        }
        if (kept) kept->at = at;
    }
    else
    {
        // One instance at a time there (nextInstance()): those the region has room for in it.
        const unsigned room = batch.capacity / batch.texels;
        if (first < room)
            std::memcpy(texels + 4 * (std::size_t(batch.base) + std::size_t(first) * batch.texels), data,
                        floats * std::min(count, room - first) * sizeof(float));
        if (kept) kept->at = ~0u;
        wrote = true;
    }
    // A batch that outgrew its region: every instance also where it moves (gatherOverflow() copies them there).
    const unsigned moved = _state._movedBase[b];
    if (moved != ~0u)
        std::memcpy(texels + 4 * (std::size_t(moved) + std::size_t(first) * batch.texels), data,
                    floats * count * sizeof(float));
}

} // namespace detail
} // namespace osgActor
