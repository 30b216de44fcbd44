#include <osgActor/core/ik/DlsIkJob>
#include <osgActor/core/ik/IkKinematics>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace osgActor {

namespace {

// Damping, as fractions of the chain's length (lambda has the Jacobian's unit, model units per radian).
constexpr double kInitialDamping = 1e-2;
constexpr double kSmallestDamping = 1e-7;
constexpr double kLargestDamping = 1e1;
// Largest change of one DOF in one step (radians or model units / chain length): beyond it the linear model lies.
constexpr double kLargestStep = 0.5;
// Restarts from a kicked pose when the solve stalls away from the goal (see kickDofs).
constexpr unsigned kMaxKicks = 64;
// A step that lowers the cost by less than this fraction is slow; this many in a row are a stall.
constexpr double kSlowProgress = 1e-2;
constexpr unsigned kMaxSlowSteps = 5;

/** Solves a x = b for a symmetric positive definite n x n matrix (n <= 6) by Cholesky; a is overwritten. False if
  * a is not positive definite (it always is with lambda > 0, short of overflow). */
bool solveSymmetric(double a[6][6], double b[6], unsigned n)
{
    for (unsigned j = 0; j < n; ++j)
    {
        double diagonal = a[j][j];
        for (unsigned k = 0; k < j; ++k) diagonal -= a[j][k] * a[j][k];
        if (!(diagonal > 0.0)) return false;
        a[j][j] = std::sqrt(diagonal);
        for (unsigned i = j + 1; i < n; ++i)
        {
            double sum = a[i][j];
            for (unsigned k = 0; k < j; ++k) sum -= a[i][k] * a[j][k];
            a[i][j] = sum / a[j][j];
        }
    }
    for (unsigned i = 0; i < n; ++i) // L y = b
    {
        for (unsigned k = 0; k < i; ++k) b[i] -= a[i][k] * b[k];
        b[i] /= a[i][i];
    }
    for (unsigned i = n; i-- > 0;) // L^T x = y
    {
        for (unsigned k = i + 1; k < n; ++k) b[i] -= a[k][i] * b[k];
        b[i] /= a[i][i];
    }
    return true;
}

/** One damped least squares step over the unlocked DOFs, dq = W J^T (J W J^T + lambda^2 I)^-1 e, shortened so no
  * DOF moves more than kLargestStep, written as dofs = saved + dq (not yet clamped). False if the system is
  * singular. */
bool dampedStep(const IkChain& c, const IkWorkspace& ws, unsigned rows, double lambda, const double error[6],
                double* dofs)
{
    const unsigned n = c.getNumDofs();
    double a[6][6] = {};
    for (unsigned d = 0; d < n; ++d)
    {
        if (ws.locked[d]) continue;
        const double w = c.getDof(d).weight;
        double column[6];
        for (unsigned r = 0; r < 3; ++r) column[r] = ws.jacobianPosition[d][r];
        for (unsigned r = 0; r < 3; ++r) column[3 + r] = ws.jacobianOrientation[d][r];
        for (unsigned i = 0; i < rows; ++i)
            for (unsigned j = 0; j <= i; ++j) a[i][j] += w * column[i] * column[j];
    }
    for (unsigned i = 0; i < rows; ++i)
    {
        for (unsigned j = i + 1; j < rows; ++j) a[i][j] = a[j][i];
        a[i][i] += lambda * lambda;
    }
    double y[6];
    std::copy(error, error + 6, y);
    if (!solveSymmetric(a, y, rows)) return false;

    const double length = c.getLength();
    double largest = 0.0;
    for (unsigned d = 0; d < n; ++d)
    {
        if (ws.locked[d]) continue;
        double step = glm::dot(ws.jacobianPosition[d], glm::dvec3(y[0], y[1], y[2]));
        if (rows == 6) step += glm::dot(ws.jacobianOrientation[d], glm::dvec3(y[3], y[4], y[5]));
        step *= c.getDof(d).weight;
        dofs[c.getDof(d).dof] = step;
        largest = std::max(largest, std::abs(step) * (isRotation(c.getDof(d).type) ? 1.0 : 1.0 / length));
    }
    const double shrink = largest > kLargestStep ? kLargestStep / largest : 1.0;
    for (unsigned d = 0; d < n; ++d)
    {
        const unsigned dof = c.getDof(d).dof;
        dofs[dof] = ws.savedDofs[d] + (ws.locked[d] ? 0.0 : dofs[dof] * shrink);
    }
    return true;
}

double cost(const IkError& error, double length)
{
    return glm::dot(error.position, error.position) + length * length * glm::dot(error.rotation, error.rotation);
}

} // namespace

bool DlsIkJob::run()
{
    result = IkResult();
    if (!validate()) return false;
    const IkChain& c = *chain;
    IkWorkspace& ws = *workspace;
    const unsigned n = c.getNumDofs();
    const double length = c.getLength();
    const bool orient = goal->hasOrientation;
    const unsigned rows = orient ? 6u : 3u;
    const glm::dmat3 goalRotation = orient ? glm::mat3_cast(glm::normalize(goal->orientation)) : glm::dmat3(1.0);

    startChainPose(*this);
    for (unsigned d = 0; d < n; ++d) ws.savedDofs[d] = dofs[c.getDof(d).dof];
    IkError error = measureIkError(*goal, goalRotation, ws);
    double bestCost = cost(error, length);
    double lambda = kInitialDamping * length;
    bool jacobianCurrent = false;
    unsigned steps = 0;
    // The best pose of earlier restarts, should a kick lead nowhere better.
    IkError earlierBestError;
    double earlierBestCost = std::numeric_limits<double>::infinity();
    unsigned kicks = 0;
    unsigned slowSteps = 0;
    // A stall: no DOF can move, or no step lowers the error however short. Kick and go on, or give up.
    auto restartAfterStall = [&]() {
        if (kicks == kMaxKicks || steps >= c.getMaxIterations()) return false;
        if (bestCost < earlierBestCost)
        {
            earlierBestCost = bestCost;
            earlierBestError = error;
            ws.bestDofs = ws.savedDofs;
        }
        kickDofs(c, ws, kicks++, dofs);
        computeChainPose(*definition, c, rootParentModel, dofs, ws);
        error = measureIkError(*goal, goalRotation, ws);
        bestCost = cost(error, length);
        for (unsigned d = 0; d < n; ++d) ws.savedDofs[d] = dofs[c.getDof(d).dof];
        lambda = kInitialDamping * length;
        jacobianCurrent = false;
        return true;
    };
    while (!withinTolerance(c, *goal, error) && steps < c.getMaxIterations())
    {
        ++steps;
        // The error to close, the orientation part in model units (radians times the chain's length).
        double e[6];
        for (unsigned r = 0; r < 3; ++r) e[r] = error.position[r];
        for (unsigned r = 0; r < 3; ++r) e[3 + r] = length * error.rotation[r];

        if (!jacobianCurrent)
        {
            computeDofAxes(*definition, c, dofs, ws);
            unsigned numFree = 0;
            for (unsigned d = 0; d < n; ++d)
            {
                const IkChainDof& chainDof = c.getDof(d);
                const bool rotation = isRotation(chainDof.type);
                ws.jacobianPosition[d] =
                    rotation ? glm::cross(ws.axis[d], ws.effectorPosition - ws.pivot[d]) : ws.axis[d];
                ws.jacobianOrientation[d] = rotation ? ws.axis[d] * length : glm::dvec3(0.0);
                // A DOF on a limit that the error pushes outward sits this step out.
                double push = glm::dot(ws.jacobianPosition[d], error.position);
                if (orient) push += length * glm::dot(ws.jacobianOrientation[d], error.rotation);
                const double value = dofs[chainDof.dof];
                ws.locked[d] = ws.frozen[d] || (value >= chainDof.max && push > 0.0) ||
                                       (value <= chainDof.min && push < 0.0)
                                   ? 1
                                   : 0;
                numFree += ws.locked[d] ? 0u : 1u;
            }
            jacobianCurrent = true;
            if (numFree == 0) // every DOF is against a limit or frozen: nothing can move
            {
                if (restartAfterStall()) continue;
                break;
            }
        }

        // A DOF the step would carry past a limit it already sits on is locked and the step solved again without
        // it, so the others make up for it rather than the clamp spoiling the step.
        bool solved = false;
        for (unsigned pass = 0; pass < 4; ++pass)
        {
            solved = dampedStep(c, ws, rows, lambda, e, dofs);
            if (!solved) break;
            bool relocked = false;
            for (unsigned d = 0; d < n; ++d)
            {
                const IkChainDof& chainDof = c.getDof(d);
                const double value = dofs[chainDof.dof], saved = ws.savedDofs[d];
                if (ws.locked[d] || !((value > chainDof.max && saved >= chainDof.max) ||
                                      (value < chainDof.min && saved <= chainDof.min)))
                    continue;
                ws.locked[d] = 1;
                dofs[chainDof.dof] = saved;
                relocked = true;
            }
            if (!relocked) break;
        }
        if (!solved) break;
        for (const IkChainDof& chainDof : c.getDofs())
            dofs[chainDof.dof] = std::min(std::max(dofs[chainDof.dof], chainDof.min), chainDof.max);

        computeChainPose(*definition, c, rootParentModel, dofs, ws);
        const IkError trial = measureIkError(*goal, goalRotation, ws);
        const double trialCost = cost(trial, length);
        if (trialCost < bestCost)
        {
            // Creeping (a chain grinding along its limits) counts as a stall after a while.
            slowSteps = trialCost > bestCost * (1.0 - kSlowProgress) ? slowSteps + 1 : 0;
            error = trial;
            bestCost = trialCost;
            for (unsigned d = 0; d < n; ++d) ws.savedDofs[d] = dofs[c.getDof(d).dof];
            lambda = std::max(lambda * 0.5, kSmallestDamping * length);
            jacobianCurrent = false;
            if (slowSteps >= kMaxSlowSteps && !withinTolerance(c, *goal, error))
            {
                slowSteps = 0;
                if (!restartAfterStall()) break;
            }
        }
        else
        {
            for (unsigned d = 0; d < n; ++d) dofs[c.getDof(d).dof] = ws.savedDofs[d];
            lambda *= 4.0;
            // No step helps: a local best, a saddle, or the closest the chain gets to a goal out of reach.
            if (lambda > kLargestDamping * length && !restartAfterStall()) break;
        }
    }
    if (earlierBestCost < bestCost)
    {
        for (unsigned d = 0; d < n; ++d) dofs[c.getDof(d).dof] = ws.bestDofs[d];
        error = earlierBestError;
    }
    setIkResult(c, *goal, error, steps, result);
    return true;
}

} // namespace osgActor
