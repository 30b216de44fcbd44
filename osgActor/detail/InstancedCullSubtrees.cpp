// The subtrees an instanced actor hands the visitor (InstancedActorGroup): nodes below its joints, or in its own
// frame, that the ordinary traversal would cull (a prop in a hand, a hidden joint, a switch, a user's node), noted
// where the actor's cull reaches them and traversed on the cull thread in the frames the ordinary traversal would give
// them, while the rest of the actor is instanced.
#include <osgActor/detail/InstancedCull.h>

#include <osgActor/ActorNode>

#include <osg/CullStack>
#include <osgUtil/CullVisitor>

#include <algorithm>
#include <cstddef>

namespace osgActor {
namespace detail {

void InstancedCull::noteSubtree(InstancedCullState::PlanVerdict& verdict, unsigned stepIndex)
{
    // The joints above the step, the actor's child first: its frame's joint and that joint's parents (all planned
    // joints, since below one that is not the plan holds no step).
    const std::vector<ActorCullPlan::Joint>& joints = verdict.plan->getJoints();
    const std::size_t start = verdict.subtreePath.size();
    for (int j = verdict.plan->getSteps()[stepIndex].joint; j >= 0; j = joints[static_cast<std::size_t>(j)].parent)
        verdict.subtreePath.push_back(joints[static_cast<std::size_t>(j)].node);
    std::reverse(verdict.subtreePath.begin() + static_cast<std::ptrdiff_t>(start), verdict.subtreePath.end());
    verdict.subtrees.push_back(stepIndex);
    verdict.subtreePathStart.push_back(static_cast<unsigned>(verdict.subtreePath.size()));
    verdict.batchOfStep.push_back(InstancedCullState::PlanVerdict::kSubtree);
}

void InstancedCull::visitSubtree(const InstancedCullState::PlanVerdict& verdict, unsigned k)
{
    const Step& step = verdict.plan->getSteps()[verdict.subtrees[k]];
    const osg::Matrixd& modelView = _scratch->modelViews[static_cast<std::size_t>(step.joint + 1)];
    _scratch->subtreeVisits.push_back({&verdict, k, modelView});
    if (_recording) _recording->subtreeVisits.emplace_back(k, modelView);
}

void InstancedCull::handOverSubtrees(ActorNode& actor, std::size_t firstVisit)
{
    const unsigned numVisits = static_cast<unsigned>(_scratch->subtreeVisits.size() - firstVisit);
    if (_outcome)
    {
        _outcome->firstSubtree = static_cast<unsigned>(firstVisit);
        _outcome->numSubtrees = numVisits;
    }
    else if (numVisits)
    {
        traverseSubtrees(actor, *_scratch, static_cast<unsigned>(firstVisit), numVisits);
        _scratch->subtreeVisits.resize(firstVisit);
    }
}

namespace {

/** osg::CullStack's list of model-view matrices the visitor reuses from frame to frame (protected there). */
struct CullStackMatrices : osg::CullStack
{
    static osg::RefMatrix* reuse(osg::CullStack& stack, const osg::Matrix& value)
    {
        osg::RefMatrix* (osg::CullStack::*const take)(const osg::Matrix&) = &CullStackMatrices::createOrReuseMatrix;
        return (stack.*take)(value);
    }
};

} // namespace

void InstancedCull::traverseSubtrees(ActorNode& actor, const InstancedCullState::ActorScratch& scratch, unsigned first,
                                     unsigned count)
{
    _cv.pushOntoNodePath(&actor);
    for (unsigned v = first; v < first + count; ++v)
    {
        const InstancedCullState::ActorScratch::SubtreeVisit& visit = scratch.subtreeVisits[v];
        const InstancedCullState::PlanVerdict& verdict = *visit.verdict;
        const unsigned pathBegin = verdict.subtreePathStart[visit.subtree];
        const unsigned pathEnd = verdict.subtreePathStart[visit.subtree + 1];
        for (unsigned p = pathBegin; p < pathEnd; ++p) _cv.pushOntoNodePath(verdict.subtreePath[p]);
        // A relative push: the visitor derives the culling set and the eye from this matrix and the projection alone,
        // as where it entered the actor and its joints (ActorCull::cullPreparedBeforeEntering()).
        _cv.pushModelViewMatrix(CullStackMatrices::reuse(_cv, visit.modelView), osg::Transform::RELATIVE_RF);
        verdict.plan->getSteps()[verdict.subtrees[visit.subtree]].node->accept(_cv);
        _cv.popModelViewMatrix();
        for (unsigned p = pathBegin; p < pathEnd; ++p) _cv.popFromNodePath();
    }
    _cv.popFromNodePath();
}

} // namespace detail
} // namespace osgActor
