// The two-bone round in the root's rotation frame ("hip frame" below: model = rootPivot + G * R * v, with G the
// rotation of the root's parent times the root's offset and R the root's articulation rotation, the unknown). In that
// frame the middle joint's pivot, its hinge axis and the effector below it do not depend on R, so the bend is solved
// there first, then R is built outright from two frames, with no forward kinematics of the chain.
#include <osgActor/core/ik/TwoBoneClosedForm>
#include <osgActor/core/ik/Arctangent>
#include <osgActor/core/ik/IkKinematics>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

namespace {

/** The product of a joint's rotation slots [first, end) in product order (local space), from the DOF values. */
glm::dmat3 slotProduct(const JointKinematics& k, unsigned first, unsigned end, const double* dofs)
{
    glm::dmat3 m(1.0);
    for (unsigned r = first; r < end; ++r)
    {
        const double angle = dofs[k.rotationDof[r]];
        const double c = std::cos(angle), s = std::sin(angle);
        const unsigned i = (k.rotationAxis[r] + 1u) % 3u, j = (k.rotationAxis[r] + 2u) % 3u;
        const glm::dvec3 ci = m[i], cj = m[j];
        m[i] = c * ci + s * cj;
        m[j] = -s * ci + c * cj;
    }
    return m;
}

/** m * R_axis(angle) from the angle's cosine and sine: only the two columns other than the axis mix. */
glm::dmat3 postRotate(const glm::dmat3& m, unsigned axis, double c, double s)
{
    const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
    glm::dmat3 result = m;
    result[i] = c * m[i] + s * m[j];
    result[j] = -s * m[i] + c * m[j];
    return result;
}

/** The rotation turning the frame (x along from, y toward fromSide) onto the frame (x along to, y toward toSide);
  * false where a side is undefined (within smallLength of its direction's line). The frames are left unnormalised
  * (y scaled by |x|^2, z = x cross y) and the rotation is the sum over their axes of target_k source_k^T / (|target_k|
  * |source_k|): two square roots and two divisions where normalising six vectors would take twelve. */
bool alignFrames(const glm::dvec3& from, const glm::dvec3& fromSide, const glm::dvec3& to, const glm::dvec3& toSide,
                 double smallLength, glm::dmat3& rotation)
{
    const double fromLength2 = glm::dot(from, from), toLength2 = glm::dot(to, to);
    const glm::dvec3 fromY = fromSide * fromLength2 - from * glm::dot(from, fromSide);
    const glm::dvec3 toY = toSide * toLength2 - to * glm::dot(to, toSide);
    const double fromY2 = glm::dot(fromY, fromY), toY2 = glm::dot(toY, toY);
    // |fromY| / |from|^2 is the side's distance from the direction's line.
    const double small2 = smallLength * smallLength;
    if (!(fromY2 >= small2 * fromLength2 * fromLength2) || !(toY2 >= small2 * toLength2 * toLength2)) return false;
    const glm::dvec3 fromZ = glm::cross(from, fromY), toZ = glm::cross(to, toY); // |z| = |x| |y|
    const double xScale = 1.0 / std::sqrt(fromLength2 * toLength2);
    const double yScale = 1.0 / std::sqrt(fromY2 * toY2);
    const double zScale = xScale * yScale;
    for (unsigned column = 0; column < 3; ++column)
        rotation[column] =
            to * (xScale * from[column]) + toY * (yScale * fromY[column]) + toZ * (zScale * fromZ[column]);
    return true;
}

unsigned freeRotations(const IkChain& chain, const IkWorkspace& workspace, unsigned first, unsigned end)
{
    unsigned count = 0;
    for (unsigned d = first; d < end; ++d)
        count += isRotation(chain.getDof(d).type) && !workspace.frozen[d] ? 1u : 0u;
    return count;
}

} // namespace

bool solveTwoBoneClosedForm(IkJob& job)
{
    const IkChain& chain = *job.chain;
    const ActorDefinition& definition = *job.definition;
    const IkWorkspace& ws = *job.workspace;
    const IkGoal& goal = *job.goal;
    double* dofs = job.dofs;
    const JointKinematics& root = definition.getKinematics(chain.getJoint(0));
    const JointKinematics& middle = definition.getKinematics(chain.getJoint(1));
    const JointKinematics& effector = definition.getKinematics(chain.getJoint(2));
    const unsigned rootEnd = chain.getFirstJointDof(1);
    const unsigned effectorFirst = chain.getFirstJointDof(2);
    const unsigned numDofs = chain.getNumDofs();

    // The case taken here (TwoBoneClosedForm says which).
    if (root.numRotations != 3 || freeRotations(chain, ws, 0, rootEnd) != 3) return false;
    const bool orient = goal.hasOrientation;
    if (orient && (effector.numRotations != 3 || freeRotations(chain, ws, effectorFirst, numDofs) != 3)) return false;
    for (const IkChainDof& d : chain.getDofs())
        if (dofs[d.dof] < d.min || dofs[d.dof] > d.max) return false;

    const double length = chain.getLength();
    const double small = 1e-12 * length;
    const glm::dmat3 goalRotation = orient ? glm::mat3_cast(glm::normalize(goal.orientation)) : glm::dmat3(1.0);

    // The root: its pivot (model space) and G, the hip frame's rotation.
    const glm::dmat3 parentRotation(job.rootParentModel);
    const glm::dmat3 rootOffsetRotation(root.offset);
    const glm::dmat3 frame = root.offsetIsTranslation ? parentRotation : parentRotation * rootOffsetRotation;
    const glm::dvec3 rootSlide = jointSlide(root, dofs);
    const bool rootSlidesFirst = root.translationMode == TranslationMode::BeforeRotation;
    const glm::dvec3 rootPivot(job.rootParentModel *
                               glm::dvec4(glm::dvec3(root.offset[3]) + (rootSlidesFirst ? rootOffsetRotation * rootSlide
                                                                                        : glm::dvec3(0.0)),
                                          1.0));
    const glm::dvec3 rootSlideAfter = rootSlidesFirst ? glm::dvec3(0.0) : rootSlide;

    // The middle joint in the hip frame: its pivot, and the frame its bend rotates in (the offset and the rotation
    // slots before the bend's; those and the slots after it are held).
    const int bend = chain.getTwoBoneBendDof();
    const IkChainDof& bendDof = chain.getDof(static_cast<unsigned>(bend));
    const unsigned slot = bendDof.rotationSlot;
    const unsigned axis = middle.rotationAxis[slot];
    const glm::dmat3 middleOffsetRotation(middle.offset);
    const glm::dvec3 middleSlide = jointSlide(middle, dofs);
    const bool middleSlidesFirst = middle.translationMode == TranslationMode::BeforeRotation;
    const glm::dvec3 middlePivot = rootSlideAfter + glm::dvec3(middle.offset[3]) +
                                   (middleSlidesFirst ? middleOffsetRotation * middleSlide : glm::dvec3(0.0));
    // (Skeletons mostly have offsets without rotation and a single hinge: the products with identities are skipped.)
    const bool bendFrameTurns = !middle.offsetIsTranslation || slot > 0;
    const glm::dmat3 bendFrame =
        slot == 0 ? middleOffsetRotation : middleOffsetRotation * slotProduct(middle, 0, slot, dofs);
    const bool turnsAfterBend = slot + 1u < middle.numRotations;
    const glm::dmat3 afterBend =
        turnsAfterBend ? slotProduct(middle, slot + 1u, middle.numRotations, dofs) : glm::dmat3(1.0);

    // The point the limb aims, in the frame right after the bend (q), and where it must go (target, model space).
    // With an orientation goal the effector's frame will be the goal's, so the limb aims the effector's pivot where
    // the goal frame puts it and the effector point follows exactly; otherwise it aims the effector point itself.
    const glm::dvec3 effectorSlide = jointSlide(effector, dofs);
    const bool effectorSlidesFirst = effector.translationMode == TranslationMode::BeforeRotation;
    const glm::dmat3 effectorOffsetRotation(effector.offset);
    const glm::dvec3 effectorPivot = (middleSlidesFirst ? glm::dvec3(0.0) : middleSlide) +
                                     glm::dvec3(effector.offset[3]) +
                                     (effectorSlidesFirst ? effectorOffsetRotation * effectorSlide : glm::dvec3(0.0));
    // The effector point from the effector's pivot, in the effector's rotation frame.
    const glm::dvec3 beyondPivot = (effectorSlidesFirst ? glm::dvec3(0.0) : effectorSlide) + chain.getEffectorOffset();
    glm::dvec3 q = effectorPivot;
    glm::dvec3 target = goal.position;
    if (orient)
        target -= goalRotation * beyondPivot;
    else if (beyondPivot != glm::dvec3(0.0))
        q += effectorOffsetRotation * (slotProduct(effector, 0, effector.numRotations, dofs) * beyondPivot);
    if (turnsAfterBend) q = afterBend * q;

    const glm::dvec3 toGoal = target - rootPivot;
    const double wanted2 = glm::dot(toGoal, toGoal);
    if (!(wanted2 > small * small)) return false; // no direction to aim at

    // 1. Bend: |middlePivot + bendFrame * R_axis(angle) * q| = wanted, i.e. with u the root pivot seen from the
    //    middle pivot in the bend frame, |q|^2 + |u|^2 - 2 u . R_axis(angle) q = wanted^2: a cos + b sin = c.
    //    The bends to try, best first, each with its cosine and sine; a second one only where two reach.
    double bends[2] = {dofs[bendDof.dof], 0.0}, cosines[2] = {0.0, 0.0}, sines[2] = {0.0, 0.0};
    unsigned numBends = 1;
    bool haveCosine = false;
    if (!ws.frozen[static_cast<unsigned>(bend)])
    {
        const glm::dvec3 u = bendFrameTurns ? -(glm::transpose(bendFrame) * middlePivot) : -middlePivot;
        const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
        const double a = u[i] * q[i] + u[j] * q[j];
        const double b = u[j] * q[i] - u[i] * q[j];
        const double sumSquares = glm::dot(q, q) + glm::dot(u, u);
        const double c = 0.5 * (sumSquares - wanted2) - u[axis] * q[axis];
        const double amplitude2 = a * a + b * b;
        if (amplitude2 > small * small * length * length)
        {
            // The two angles with a cos + b sin = c: cos = (a c -+ b w) / r^2, sin = (b c +- a w) / r^2 with r^2 =
            // a^2 + b^2, w = sqrt(r^2 - c^2). Out of reach (|c| > r) both are the nearest, c clamped to +-r.
            const bool reachable = c * c <= amplitude2;
            const double cc = reachable ? c : std::copysign(std::sqrt(amplitude2), c);
            const double w = std::sqrt(std::max(0.0, amplitude2 - cc * cc));
            const double inverse = 1.0 / amplitude2;
            const double solutionCosines[2] = {(a * cc - b * w) * inverse, (a * cc + b * w) * inverse};
            const double solutionSines[2] = {(b * cc + a * w) * inverse, (b * cc - a * w) * inverse};
            const double solutions[2] = {arctangent2(solutionSines[0], solutionCosines[0]),
                                         arctangent2(solutionSines[1], solutionCosines[1])};
            const double current = bends[0];
            double turned[2] = {0.0, 0.0};
            const bool inside[2] = {turnWithinLimits(solutions[0], bendDof.min, bendDof.max, current, turned[0]),
                                    turnWithinLimits(solutions[1], bendDof.min, bendDof.max, current, turned[1])};
            if (reachable && (inside[0] || inside[1]))
            {
                // The solutions within the limits reach: the nearer the current angle first.
                const unsigned first =
                    inside[0] && (!inside[1] || std::abs(turned[0] - current) <= std::abs(turned[1] - current)) ? 0u
                                                                                                              : 1u;
                numBends = inside[0] && inside[1] ? 2u : 1u;
                for (unsigned n = 0; n < numBends; ++n)
                {
                    const unsigned s = n == 0 ? first : 1u - first;
                    bends[n] = turned[s];
                    cosines[n] = solutionCosines[s];
                    sines[n] = solutionSines[s];
                }
            }
            else
            {
                // Out of reach, or the solutions lie beyond the limits: the one that comes closer once clamped,
                // ties going to the one nearer the current angle.
                const double wanted = std::sqrt(wanted2);
                double bestMiss = 0.0;
                for (unsigned s = 0; s < 2; ++s)
                {
                    double candidate = turned[s], cx = solutionCosines[s], sx = solutionSines[s];
                    if (!inside[s])
                    {
                        candidate = fitAngleToLimits(solutions[s], bendDof.min, bendDof.max, current);
                        cx = std::cos(candidate);
                        sx = std::sin(candidate);
                    }
                    const double reach =
                        std::sqrt(std::max(0.0, sumSquares - 2.0 * (u[axis] * q[axis] + a * cx + b * sx)));
                    const double miss = std::abs(reach - wanted);
                    if (s == 0 || miss < bestMiss - small ||
                        (miss < bestMiss + small && std::abs(candidate - current) < std::abs(bends[0] - current)))
                    {
                        bends[0] = candidate;
                        cosines[0] = cx;
                        sines[0] = sx;
                        bestMiss = miss;
                    }
                }
            }
            haveCosine = true;
        }
    }
    if (!haveCosine)
    {
        cosines[0] = std::cos(bends[0]);
        sines[0] = std::sin(bends[0]);
    }

    // 2. and 3. for each bend in turn, until one needs no clamping.
    const glm::dmat3 toHipFrame = glm::transpose(frame);
    const glm::dvec3 goalInHipFrame = toHipFrame * toGoal;
    for (unsigned n = 0; n < numBends; ++n)
    {
        const glm::dvec3 bent = rotateAboutAxis(q, axis, cosines[n], sines[n]);
        const glm::dvec3 reach = middlePivot + (bendFrameTurns ? bendFrame * bent : bent);
        if (!(glm::dot(reach, reach) > small * small)) return false;

        // 2. Aim: R turns the limb's frame (the reach, the middle pivot to its side) onto the goal's (the goal, the
        //    pole to its side); without a pole, the shortest arc from where the current R puts the reach.
        glm::dmat3 rotation;
        if (!goal.hasPole || !alignFrames(reach, middlePivot, goalInHipFrame, toHipFrame * (goal.pole - rootPivot),
                                          1e-9 * length, rotation))
        {
            const double current[3] = {dofs[root.rotationDof[0]], dofs[root.rotationDof[1]],
                                       dofs[root.rotationDof[2]]};
            const glm::dmat3 currentRotation = composeEuler(root, current);
            rotation = shortestArc(currentRotation * reach, goalInHipFrame) * currentRotation;
        }
        double rootAngles[3];
        if (!fitJointRotation(definition, root, rotation, dofs, rootAngles)) continue;

        // 3. Orientation: the effector's rotations take the goal frame outright.
        double effectorAngles[3];
        if (orient)
        {
            glm::dmat3 middleRotation = frame * rotation * postRotate(bendFrame, axis, cosines[n], sines[n]);
            if (turnsAfterBend) middleRotation = middleRotation * afterBend;
            const glm::dmat3 effectorFrame =
                effector.offsetIsTranslation ? middleRotation : middleRotation * effectorOffsetRotation;
            if (!fitJointRotation(definition, effector, glm::transpose(effectorFrame) * goalRotation, dofs,
                                  effectorAngles))
                continue;
        }

        // Every step took its value exactly (the bend perhaps clamped): the effector is where the construction puts
        // it (the random-target tests check this against the actor's own forward kinematics).
        for (unsigned r = 0; r < 3; ++r) dofs[root.rotationDof[r]] = rootAngles[r];
        dofs[bendDof.dof] = bends[n];
        if (orient)
            for (unsigned r = 0; r < 3; ++r) dofs[effector.rotationDof[r]] = effectorAngles[r];
        IkError error;
        error.position = toGoal - frame * (rotation * reach);
        error.positionNorm = glm::length(error.position);
        setIkResult(chain, goal, error, 1, job.result);
        return true;
    }
    return false; // every bend needs a clamped aim or orientation
}

} // namespace osgActor
