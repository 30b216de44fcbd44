#include <osgActor/core/ik/TwoBoneIkJob>
#include <osgActor/core/ik/CcdIkJob>
#include <osgActor/core/ik/DlsIkJob>
#include <osgActor/core/ik/IkKinematics>
#include <osgActor/core/ik/TwoBoneClosedForm>

#include <glm/ext/scalar_constants.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

namespace {

/** Sets a joint's three rotation DOFs so its articulation rotation (local space) is as close to target as the
  * limits allow (fitJointRotation). Returns false when it had to clamp. */
bool setJointRotation(const ActorDefinition& definition, const JointKinematics& k, const glm::dmat3& target,
                      double* dofs)
{
    double angles[3];
    const bool exact = fitJointRotation(definition, k, target, dofs, angles);
    for (unsigned r = 0; r < 3; ++r) dofs[k.rotationDof[r]] = angles[r];
    return exact;
}

/** The rotation (model space) turning the orthonormal frame (x along from, y toward fromSide) onto the frame (x along
  * to, y toward toSide); the shortest arc where a side is undefined (along the direction). */
glm::dmat3 aimWithPole(const glm::dvec3& from, const glm::dvec3& fromSide, const glm::dvec3& to,
                       const glm::dvec3& toSide, double smallLength)
{
    const glm::dvec3 xs = glm::normalize(from), xt = glm::normalize(to);
    glm::dvec3 ys = fromSide - xs * glm::dot(xs, fromSide);
    glm::dvec3 yt = toSide - xt * glm::dot(xt, toSide);
    if (glm::length(ys) < smallLength || glm::length(yt) < smallLength) return shortestArc(from, to);
    ys = glm::normalize(ys);
    yt = glm::normalize(yt);
    const glm::dmat3 source(xs, ys, glm::cross(xs, ys));
    const glm::dmat3 target(xt, yt, glm::cross(xt, yt));
    return target * glm::transpose(source);
}

double cost(const IkError& error, double length)
{
    return glm::dot(error.position, error.position) + length * length * error.angle * error.angle;
}

} // namespace

bool TwoBoneIkJob::run()
{
    result = IkResult();
    if (!validate()) return false;
    // The common case in closed form, without forward kinematics; the rounds below take the rest.
    if (solveTwoBoneClosedForm(*this)) return true;
    const IkChain& c = *chain;
    IkWorkspace& ws = *workspace;
    const ActorDefinition& def = *definition;
    const JointKinematics& rootKinematics = def.getKinematics(c.getJoint(0));
    const JointKinematics& effectorKinematics = def.getKinematics(c.getJoint(2));
    const unsigned bend = static_cast<unsigned>(c.getTwoBoneBendDof());
    const IkChainDof& bendDof = c.getDof(bend);
    const unsigned rootEnd = c.getFirstJointDof(1);
    const unsigned effectorFirst = c.getFirstJointDof(2);
    const unsigned numDofs = c.getNumDofs();
    const double length = c.getLength();
    const double small = 1e-12 * length;

    // Three free rotations on a joint: its rotation can be set outright by Euler decomposition.
    auto freeRotations = [&](unsigned first, unsigned end) {
        unsigned count = 0;
        for (unsigned d = first; d < end; ++d) count += isRotation(c.getDof(d).type) && !ws.frozen[d] ? 1u : 0u;
        return count;
    };
    bool analyticAim = rootKinematics.numRotations == 3 && freeRotations(0, rootEnd) == 3;
    const bool orient = goal->hasOrientation && freeRotations(effectorFirst, numDofs) > 0;
    const bool analyticOrientation = effectorKinematics.numRotations == 3 && freeRotations(effectorFirst, numDofs) == 3;
    const glm::dmat3 goalRotation =
        goal->hasOrientation ? glm::mat3_cast(glm::normalize(goal->orientation)) : glm::dmat3(1.0);
    startChainPose(*this);
    // When the effector's frame can take the goal's orientation outright, the effector point will lie at
    // goalRotation * beyondPivot from the effector's pivot, so the limb aims the pivot there and the point follows
    // exactly. Otherwise the limb aims the effector point itself.
    const bool offsetFollowsGoal = orient && analyticOrientation;
    // The effector point from the effector's pivot, in its rotation frame (a slide after rotation turns with it).
    const glm::dvec3 beyondPivot =
        (effectorKinematics.translationMode == TranslationMode::AfterRotation ? jointSlide(effectorKinematics, dofs)
                                                                               : glm::dvec3(0.0)) +
        c.getEffectorOffset();
    const glm::dvec3 target = offsetFollowsGoal ? goal->position - goalRotation * beyondPivot : goal->position;

    IkError error = measureIkError(*goal, goalRotation, ws);
    double previousCost = cost(error, length);
    unsigned rounds = 0;
    while (!withinTolerance(c, *goal, error) && rounds < c.getMaxIterations())
    {
        ++rounds;
        computeJointDofAxes(def, c, 1, dofs, ws); // the bend's axis and pivot
        const glm::dvec3 rootPivot = rotationPivot(rootKinematics, ws.jointModel[0], dofs);
        const glm::dvec3 toGoal = target - rootPivot;
        glm::dvec3 tracked = offsetFollowsGoal ? rotationPivot(effectorKinematics, ws.jointModel[2], dofs)
                                               : glm::dvec3(ws.jointModel[2] * glm::dvec4(c.getEffectorOffset(), 1.0));

        // 1. Bend: |pivot + R(turn) q - rootPivot| = |toGoal|, i.e. A cos(turn) + B sin(turn) = C.
        const glm::dvec3 bendAxis = ws.axis[bend];
        const glm::dvec3 bendPivot = ws.pivot[bend];
        if (!ws.frozen[bend])
        {
            const glm::dvec3 q = tracked - bendPivot;
            const glm::dvec3 u = rootPivot - bendPivot;
            const double qAlong = glm::dot(bendAxis, q), uAlong = glm::dot(bendAxis, u);
            const glm::dvec3 qAcross = q - bendAxis * qAlong, uAcross = u - bendAxis * uAlong;
            const double a = glm::dot(uAcross, qAcross);
            const double b = glm::dot(bendAxis, glm::cross(qAcross, uAcross));
            const double k = glm::dot(q, q) + glm::dot(u, u) - 2.0 * qAlong * uAlong;
            const double wanted = glm::length(toGoal);
            const double amplitude = std::sqrt(a * a + b * b);
            if (amplitude > small * length)
            {
                const double phase = std::atan2(b, a);
                const double spread = std::acos(std::min(1.0, std::max(-1.0, 0.5 * (k - wanted * wanted) / amplitude)));
                const double current = dofs[bendDof.dof];
                double best = current, bestMiss = 0.0;
                for (unsigned s = 0; s < 2; ++s)
                {
                    const double candidate = fitAngleToLimits(current + phase + (s == 0 ? spread : -spread),
                                                              bendDof.min, bendDof.max, current);
                    const double turn = candidate - current;
                    const double reach = std::sqrt(std::max(0.0, k - 2.0 * (a * std::cos(turn) + b * std::sin(turn))));
                    const double miss = std::abs(reach - wanted);
                    if (s == 0 || miss < bestMiss - small ||
                        (miss < bestMiss + small && std::abs(turn) < std::abs(best - current)))
                    {
                        best = candidate;
                        bestMiss = miss;
                    }
                }
                const double turn = best - current;
                dofs[bendDof.dof] = best;
                tracked = bendPivot + rotateAbout(q, bendAxis, turn);
            }
        }

        // 2. Aim the root.
        const glm::dvec3 reach = tracked - rootPivot;
        bool exact = false; // the root took the aim exactly, so the tracked point is known without FK
        if (analyticAim && glm::length(toGoal) > small && glm::length(reach) > small)
        {
            const glm::dmat3 turn = goal->hasPole
                                        ? aimWithPole(reach, bendPivot - rootPivot, toGoal, goal->pole - rootPivot,
                                                      1e-9 * length)
                                        : shortestArc(reach, toGoal);
            // The root's articulation R in model space is G * R, G = parent * offset (rotation parts), so the new
            // articulation is G^T * turn * G * R.
            const glm::dmat3 frame = glm::dmat3(rootParentModel) * glm::dmat3(rootKinematics.offset);
            const glm::dmat3 target = glm::transpose(frame) * turn * glm::dmat3(ws.jointModel[0]);
            analyticAim = setJointRotation(def, rootKinematics, target, dofs);
            // Exact unless clamped, or an orientation goal the effector cannot take outright is measured below.
            exact = analyticAim && (!goal->hasOrientation || analyticOrientation);
            tracked = rootPivot + turn * reach;
        }

        // 3. Turn the effector's frame onto the goal's.
        if (orient)
        {
            computeChainPose(def, c, rootParentModel, dofs, ws);
            if (analyticOrientation)
            {
                const glm::dmat3 frame = glm::dmat3(ws.jointModel[1]) * glm::dmat3(effectorKinematics.offset);
                exact = setJointRotation(def, effectorKinematics, glm::transpose(frame) * goalRotation, dofs) && exact;
            }
            else
            {
                exact = false;
                for (unsigned sweep = 0; sweep < 3; ++sweep)
                {
                    computeDofAxes(def, c, dofs, ws);
                    runCcdSweep(c, *goal, goalRotation, 0.0, 1.0, false, effectorFirst, numDofs, dofs, ws);
                }
            }
        }

        if (exact)
        {
            // Every step took its value exactly: the effector is where the construction put it (the random-target
            // tests check this against full forward kinematics).
            error = IkError();
            error.position = target - tracked;
            error.positionNorm = glm::length(error.position);
        }
        else
        {
            computeChainPose(def, c, rootParentModel, dofs, ws);
            error = measureIkError(*goal, goalRotation, ws);
        }
        const double roundCost = cost(error, length);
        if (roundCost >= previousCost * (1.0 - 1e-9)) break; // no further progress: out of reach or stuck on limits
        previousCost = roundCost;
    }
    if (withinTolerance(c, *goal, error) || analyticAim)
    {
        setIkResult(c, *goal, error, rounds, result);
        return true;
    }

    // The aim could not be set outright (fewer than three free root rotations) or was clamped: damped least squares
    // finishes from the analytic start, on rotations only.
    for (unsigned d = 0; d < numDofs; ++d)
        if (!isRotation(c.getDof(d).type)) ws.frozen[d] |= 2; // bit 1: frozen here, not by the caller
    DlsIkJob finish;
    static_cast<IkJob&>(finish) = *this;
    finish.run();
    for (unsigned d = 0; d < numDofs; ++d) ws.frozen[d] &= 1;
    result = finish.result;
    result.iterations += rounds;
    return true;
}

} // namespace osgActor
