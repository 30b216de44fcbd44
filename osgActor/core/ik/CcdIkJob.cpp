#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/Arctangent>
#include <osgActor/core/ik/IkKinematics>
#include <osgActor/core/ik/SweepAcceleration>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

// A sweep (with its acceleration) that lowers the cost by less than this fraction is slow; this many in a row are a
// stall, answered by a restart from a kicked pose (kickDofs), at most kMaxKicks times per solve. The acceleration
// leaves few slow sweeps short of a local minimum, so three are enough to tell one.
constexpr double kSlowProgress = 1e-3;
constexpr unsigned kMaxSlowSweeps = 3;
constexpr unsigned kMaxKicks = 64;
// A sweep that leaves more than this fraction of the cost converges slowly: the solver tries SweepAcceleration's
// proposals, Anderson mixing first, then up to this many pattern moves (strides 1, 2, 4, ... times the sweep's).
constexpr double kAccelerateAbove = 0.1;
constexpr unsigned kMaxPatternTrials = 10;

/** v divided by its largest component's magnitude: the same direction, every component within [-1, 1]. */
glm::dvec3 scaledToUnitMax(const glm::dvec3& v)
{
    const double largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    return largest > 0.0 && std::isfinite(largest) ? v / largest : v;
}

/** The position objective's terms for unit axis a: C = f . t and S = a . (f x t), with f and t the parts of from
  * (effector - pivot) and to (goal - pivot) across the axis. With rescale, from and to are first brought to unit
  * size: the same best angle, computed without overflow. */
void positionTerms(const glm::dvec3& a, glm::dvec3 from, glm::dvec3 to, bool rescale, double& cosTerm,
                   double& sinTerm)
{
    if (rescale)
    {
        from = scaledToUnitMax(from);
        to = scaledToUnitMax(to);
    }
    const glm::dvec3 f = from - a * glm::dot(a, from);
    const glm::dvec3 t = to - a * glm::dot(a, to);
    cosTerm = glm::dot(f, t);
    sinTerm = glm::dot(a, glm::cross(f, t));
}

/** The angle about unit axis a (through pivot) that maximizes positionWeight * (goal - pivot) . R (effector - pivot)
  * + orientationWeight * sum_i goalAxis_i . R effectorAxis_i, i.e. that best turns the effector onto the goal.
  * Always finite: where the products overflow (a goal or an effector near the end of the double range, finite but
  * 1e300 away), the position term dwarfs any orientation term and the angle is taken from the directions alone. */
double bestAngle(const glm::dvec3& a, const glm::dvec3& pivot, const glm::dvec3& effector,
                 const glm::dmat3& effectorRotation, const glm::dvec3& goal, const glm::dmat3& goalRotation,
                 double positionWeight, double orientationWeight)
{
    // Each objective is c0 + C cos(angle) + S sin(angle); their weighted sum peaks at atan2(S, C).
    const glm::dvec3 from = effector - pivot;
    glm::dvec3 to = goal - pivot;
    if (!std::isfinite(to.x) || !std::isfinite(to.y) || !std::isfinite(to.z)) to = goal * 0.5 - pivot * 0.5;
    double cosTerm = 0.0, sinTerm = 0.0;
    if (positionWeight > 0.0)
    {
        double c, s;
        positionTerms(a, from, to, false, c, s);
        cosTerm += positionWeight * c;
        sinTerm += positionWeight * s;
    }
    if (orientationWeight > 0.0)
    {
        for (unsigned i = 0; i < 3; ++i)
        {
            const glm::dvec3& e = effectorRotation[i];
            const glm::dvec3& g = goalRotation[i];
            cosTerm += orientationWeight * (glm::dot(e, g) - glm::dot(a, e) * glm::dot(a, g));
            sinTerm += orientationWeight * glm::dot(a, glm::cross(e, g));
        }
    }
    if (!std::isfinite(cosTerm) || !std::isfinite(sinTerm))
    {
        if (!(positionWeight > 0.0)) return 0.0;
        positionTerms(a, from, to, true, cosTerm, sinTerm);
        if (!std::isfinite(cosTerm) || !std::isfinite(sinTerm)) return 0.0;
    }
    if (cosTerm * cosTerm + sinTerm * sinTerm < 1e-30) return 0.0;
    return arctangent2(sinTerm, cosTerm);
}

/** After chain DOF d turned by rotation (model space, about its pivot): the DOFs of the same joint still to come
  * in the sweep ([first, d)) whose axes lie after it in the joint's product turn with it. Those are the rotations
  * later in the product, and the slides of a joint that slides after it rotates. */
void turnLaterAxesOfJoint(const IkChain& chain, unsigned first, unsigned d, const glm::dmat3& rotation,
                          IkWorkspace& workspace)
{
    const IkChainDof& turned = chain.getDof(d);
    for (unsigned other = d; other-- > first && chain.getDof(other).chainJoint == turned.chainJoint;)
    {
        const IkChainDof& dof = chain.getDof(other);
        const bool after = isRotation(dof.type) ? dof.rotationSlot > turned.rotationSlot
                                                : dof.translationMode == TranslationMode::AfterRotation;
        if (after) workspace.axis[other] = rotation * workspace.axis[other];
    }
}

/** After chain DOF d slid by offset (model space): a joint that slides before it rotates turns about a point the
  * slide moved, so the pivots of its rotations still to come in the sweep move with it. */
void moveLaterPivotsOfJoint(const IkChain& chain, unsigned first, unsigned d, const glm::dvec3& offset,
                            IkWorkspace& workspace)
{
    const IkChainDof& slid = chain.getDof(d);
    if (slid.translationMode != TranslationMode::BeforeRotation) return;
    for (unsigned other = d; other-- > first && chain.getDof(other).chainJoint == slid.chainJoint;)
        if (isRotation(chain.getDof(other).type)) workspace.pivot[other] += offset;
}

} // namespace

void runCcdSweep(const IkChain& chain, const IkGoal& goal, const glm::dmat3& goalRotation, double positionWeight,
                 double orientationWeight, bool moveSlides, unsigned first, unsigned end, double* dofs,
                 IkWorkspace& workspace)
{
    glm::dvec3& effector = workspace.effectorPosition;
    glm::dmat3& effectorRotation = workspace.effectorRotation;
    for (unsigned d = end; d-- > first;)
    {
        if (workspace.frozen[d]) continue;
        const IkChainDof& chainDof = chain.getDof(d);
        const glm::dvec3& axis = workspace.axis[d];
        const double current = dofs[chainDof.dof];
        if (isRotation(chainDof.type))
        {
            const double angle = bestAngle(axis, workspace.pivot[d], effector, effectorRotation, goal.position,
                                           goalRotation, positionWeight, orientationWeight);
            const double next = std::min(std::max(current + chainDof.weight * angle, chainDof.min), chainDof.max);
            const double turn = next - current;
            if (turn == 0.0) continue;
            dofs[chainDof.dof] = next;
            // Everything below this DOF turns with it about its axis: the effector exactly so.
            const glm::dmat3 rotation = glm::mat3_cast(glm::angleAxis(turn, axis));
            effector = workspace.pivot[d] + rotation * (effector - workspace.pivot[d]);
            effectorRotation = rotation * effectorRotation;
            turnLaterAxesOfJoint(chain, first, d, rotation, workspace);
        }
        else if (moveSlides && positionWeight > 0.0)
        {
            const double slide = glm::dot(goal.position - effector, axis);
            const double next = std::min(std::max(current + chainDof.weight * slide, chainDof.min), chainDof.max);
            // A slide without limits toward a goal beyond the double range from here (the step overflows): stay.
            if (!std::isfinite(next)) continue;
            dofs[chainDof.dof] = next;
            const glm::dvec3 offset = axis * (next - current);
            effector += offset;
            moveLaterPivotsOfJoint(chain, first, d, offset, workspace);
        }
    }
}

bool CcdIkJob::run()
{
    result = IkResult();
    if (!validate()) return false;
    const IkChain& c = *chain;
    IkWorkspace& ws = *workspace;
    const unsigned n = c.getNumDofs();
    const glm::dmat3 goalRotation =
        goal->hasOrientation ? glm::mat3_cast(glm::normalize(goal->orientation)) : glm::dmat3(1.0);
    // The cost weighs radians like arcs on a circle of the chain's length. A sweep maximises the position dot product
    // (-|error|^2 / 2 about the goal) plus its orientation weight times the sum of the frame axes' dot products
    // (-angle^2 about the goal), so half the cost's weight makes each turn minimise the cost itself.
    const double lengthSquared = c.getLength() * c.getLength();
    const double costOrientationWeight = goal->hasOrientation ? lengthSquared : 0.0;
    const double sweepOrientationWeight = 0.5 * costOrientationWeight;
    auto cost = [&](const IkError& e) {
        return glm::dot(e.position, e.position) + costOrientationWeight * e.angle * e.angle;
    };
    auto gather = [&](double* values) {
        for (unsigned d = 0; d < n; ++d) values[d] = dofs[c.getDof(d).dof];
    };
    // Sets the chain's DOFs (chain DOF order) within their limits, frozen ones kept, and brings the pose up to date.
    auto setPose = [&](const double* values) {
        for (unsigned d = 0; d < n; ++d)
        {
            const IkChainDof& chainDof = c.getDof(d);
            if (!ws.frozen[d]) dofs[chainDof.dof] = std::min(std::max(values[d], chainDof.min), chainDof.max);
        }
        computeChainPose(*definition, c, rootParentModel, dofs, ws);
    };

    startChainPose(*this);
    IkError error = measureIkError(*goal, goalRotation, ws);
    double currentCost = cost(error);
    // The best pose before the last restart, should a kick lead nowhere better.
    IkError earlierBestError;
    double earlierBestCost = std::numeric_limits<double>::infinity();
    SweepHistory history;
    unsigned kicks = 0, slowSweeps = 0, sweeps = 0;
    while (!withinTolerance(c, *goal, error) && sweeps < c.getMaxIterations())
    {
        ++sweeps;
        gather(ws.savedDofs.data());
        computeDofAxes(*definition, c, dofs, ws);
        runCcdSweep(c, *goal, goalRotation, 1.0, sweepOrientationWeight, true, 0, n, dofs, ws);
        // The sweep tracked the effector exactly; recompute anyway so rounding cannot pile up over sweeps.
        computeChainPose(*definition, c, rootParentModel, dofs, ws);
        error = measureIkError(*goal, goalRotation, ws);
        double sweepCost = cost(error);
        gather(ws.trialDofs.data());
        history.record(c, ws.savedDofs.data(), ws.trialDofs.data(), ws);

        if (sweepCost > kAccelerateAbove * currentCost && !withinTolerance(c, *goal, error))
        {
            // Converging slowly: try the proposals of SweepAcceleration, keeping one only where it lowers the cost.
            const double* start = &ws.sweepStarts[(history.count - 1) * n];
            const double* end = &ws.sweepEnds[(history.count - 1) * n];
            auto tryPose = [&]() {
                setPose(ws.trialDofs.data());
                const IkError trial = measureIkError(*goal, goalRotation, ws);
                const double trialCost = cost(trial);
                if (!(trialCost < sweepCost)) return false;
                error = trial;
                sweepCost = trialCost;
                return true;
            };
            bool improved = proposeAndersonMix(c, ws, history, ws.trialDofs.data()) && tryPose();
            if (!improved)
            {
                // Further along the sweep's own direction, doubling the stride while it helps.
                double factor = 1.0, bestFactor = 0.0;
                for (unsigned trial = 0; trial < kMaxPatternTrials; ++trial, factor *= 2.0)
                {
                    proposePatternMove(c, start, end, factor, ws.trialDofs.data());
                    if (!tryPose()) break;
                    bestFactor = factor;
                }
                improved = bestFactor > 0.0;
                if (improved && bestFactor != factor)
                    proposePatternMove(c, start, end, bestFactor, ws.trialDofs.data());
                if (!improved || bestFactor != factor) setPose(improved ? ws.trialDofs.data() : end);
            }
        }

        slowSweeps = sweepCost > currentCost * (1.0 - kSlowProgress) ? slowSweeps + 1 : 0;
        currentCost = sweepCost;
        if (slowSweeps < kMaxSlowSweeps || kicks == kMaxKicks || withinTolerance(c, *goal, error)) continue;
        // Stalled (a hinge on its limit, a chain wound up against its limits): restart from a kicked pose.
        if (currentCost < earlierBestCost)
        {
            earlierBestCost = currentCost;
            earlierBestError = error;
            gather(ws.bestDofs.data());
        }
        kickDofs(c, ws, kicks++, dofs);
        computeChainPose(*definition, c, rootParentModel, dofs, ws);
        error = measureIkError(*goal, goalRotation, ws);
        currentCost = cost(error);
        slowSweeps = 0;
        history.clear();
    }
    if (earlierBestCost < currentCost)
    {
        for (unsigned d = 0; d < n; ++d) dofs[c.getDof(d).dof] = ws.bestDofs[d];
        error = earlierBestError;
    }
    setIkResult(c, *goal, error, sweeps, result);
    return true;
}

} // namespace osgActor
