#include <osgActor/core/ik/IkKinematics>
#include <osgActor/core/ik/Arctangent>
#include <osgActor/core/LocalMatricesJob>
#include <osgActor/core/LocalToModelJob>

#include <glm/ext/scalar_constants.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace osgActor {

void computeChainPose(const ActorDefinition& definition, const IkChain& chain, const glm::dmat4& rootParentModel,
                      const double* dofs, IkWorkspace& workspace)
{
    const std::vector<JointKinematics>& kinematics = definition.getAllKinematics();
    const unsigned numJoints = chain.getNumJoints();
    const glm::dmat4* parent = &rootParentModel;
    for (unsigned c = 0; c < numJoints; ++c)
    {
        workspace.jointModel[c] = multiplyAffine(*parent, computeJointMatrix(kinematics[chain.getJoint(c)], dofs));
        parent = &workspace.jointModel[c];
    }
    const glm::dmat4& effector = workspace.jointModel[numJoints - 1];
    workspace.effectorPosition = glm::dvec3(effector * glm::dvec4(chain.getEffectorOffset(), 1.0));
    workspace.effectorRotation = glm::dmat3(effector);
}

void startChainPose(const IkJob& job)
{
    const IkChain& chain = *job.chain;
    bool clamped = false;
    for (const IkChainDof& d : chain.getDofs())
    {
        double& value = job.dofs[d.dof];
        const double inside = std::min(std::max(value, d.min), d.max);
        clamped = clamped || inside != value;
        value = inside;
    }
    IkWorkspace& workspace = *job.workspace;
    if (!job.jointModels || clamped)
    {
        computeChainPose(*job.definition, chain, job.rootParentModel, job.dofs, workspace);
        return;
    }
    for (unsigned c = 0; c < chain.getNumJoints(); ++c) workspace.jointModel[c] = job.jointModels[chain.getJoint(c)];
    const glm::dmat4& effector = workspace.jointModel.back();
    workspace.effectorPosition = glm::dvec3(effector * glm::dvec4(chain.getEffectorOffset(), 1.0));
    workspace.effectorRotation = glm::dmat3(effector);
}

void computeDofAxes(const ActorDefinition& definition, const IkChain& chain, const double* dofs,
                    IkWorkspace& workspace)
{
    for (unsigned c = 0; c < chain.getNumJoints(); ++c) computeJointDofAxes(definition, chain, c, dofs, workspace);
}

void computeJointDofAxes(const ActorDefinition& definition, const IkChain& chain, unsigned c, const double* dofs,
                         IkWorkspace& workspace)
{
    {
        const unsigned firstDof = chain.getFirstJointDof(c);
        const unsigned endDof = chain.getFirstJointDof(c + 1);
        if (firstDof == endDof) return;
        const JointKinematics& k = definition.getKinematics(chain.getJoint(c));
        // The joint's rotation part in model space: parent * offset * R_a1 R_a2 R_a3 in either translation mode.
        const glm::dmat3 frame(workspace.jointModel[c]);
        double cosines[3], sines[3];
        for (unsigned r = 0; r < k.numRotations; ++r)
        {
            cosines[r] = std::cos(dofs[k.rotationDof[r]]);
            sines[r] = std::sin(dofs[k.rotationDof[r]]);
        }
        const glm::dvec3 pivot = rotationPivot(k, workspace.jointModel[c], dofs);
        for (unsigned d = firstDof; d < endDof; ++d)
        {
            const IkChainDof& chainDof = chain.getDof(d);
            glm::dvec3 v(0.0);
            v[axisOf(chainDof.type)] = 1.0;
            // Axis of rotation slot s: frame * R_last^T ... R_(s+1)^T * e_s (the slots after it undone). A slide
            // after rotation is along the frame's own axis; before rotation, along the frame with every rotation
            // undone.
            unsigned undoFrom = 0;
            if (isRotation(chainDof.type)) undoFrom = chainDof.rotationSlot + 1u;
            else if (k.translationMode == TranslationMode::AfterRotation) undoFrom = k.numRotations;
            for (unsigned r = undoFrom; r < k.numRotations; ++r) // R_(s+1)^T acts first
                v = rotateAboutAxis(v, k.rotationAxis[r], cosines[r], -sines[r]);
            workspace.axis[d] = frame * v;
            workspace.pivot[d] = pivot;
        }
    }
}

glm::dvec3 rotationPivot(const JointKinematics& k, const glm::dmat4& jointModel, const double* dofs)
{
    glm::dvec3 pivot(jointModel[3]);
    if (k.translationMode == TranslationMode::BeforeRotation) return pivot;
    // jointModel = parent * offset * R * T(t): its origin is the pivot moved by (its rotation part) * t.
    return pivot - glm::dmat3(jointModel) * jointSlide(k, dofs);
}

IkError measureIkError(const IkGoal& goal, const glm::dmat3& goalRotation, const IkWorkspace& workspace)
{
    IkError error;
    error.position = goal.position - workspace.effectorPosition;
    error.positionNorm = glm::length(error.position);
    if (goal.hasOrientation)
    {
        error.rotation = rotationVector(goalRotation * glm::transpose(workspace.effectorRotation));
        error.angle = glm::length(error.rotation);
    }
    return error;
}

bool withinTolerance(const IkChain& chain, const IkGoal& goal, const IkError& error)
{
    const double tolerance = chain.getTolerance();
    return error.positionNorm <= tolerance * chain.getLength() && (!goal.hasOrientation || error.angle <= tolerance);
}

void setIkResult(const IkChain& chain, const IkGoal& goal, const IkError& error, unsigned iterations,
                 IkResult& result)
{
    result.iterations = iterations;
    result.positionError = error.positionNorm;
    result.orientationError = goal.hasOrientation ? error.angle : 0.0;
    result.reached = withinTolerance(chain, goal, error);
}

namespace {

/** A number in [0, 1) from two integers (splitmix64): the same for the same inputs on every platform. */
double hashToUnit(unsigned a, unsigned b)
{
    std::uint64_t z = (std::uint64_t(a) << 32 | b) + 0x9E3779B97F4A7C15ull;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return double(z >> 11) * (1.0 / 9007199254740992.0);
}

} // namespace

void kickDofs(const IkChain& chain, const IkWorkspace& workspace, unsigned kick, double* dofs)
{
    const double pi = glm::pi<double>();
    for (unsigned d = 0; d < chain.getNumDofs(); ++d)
    {
        if (workspace.frozen[d]) continue;
        const IkChainDof& chainDof = chain.getDof(d);
        const bool rotation = isRotation(chainDof.type);
        const double value = dofs[chainDof.dof];
        double next;
        if (kick == 0)
        {
            // First a small nudge, enough to leave a saddle (a straight limb on its hinge limit).
            const double size = rotation ? 0.3 : 0.05 * chain.getLength();
            double step = d % 2 ? -size : size;
            if (value + step > chainDof.max || value + step < chainDof.min) step = -step;
            next = value + step;
        }
        else
        {
            // Then fresh starts spread over the limits (over a turn, or the chain's length, where unlimited).
            const double u = hashToUnit(kick, d);
            const double span = rotation ? 2.0 * pi : chain.getLength();
            const double lo = std::isfinite(chainDof.min) ? chainDof.min : value - 0.5 * span;
            const double hi = std::isfinite(chainDof.max) ? chainDof.max : value + 0.5 * span;
            next = lo + u * (std::min(hi, lo + 2.0 * span) - lo);
        }
        dofs[chainDof.dof] = std::min(std::max(next, chainDof.min), chainDof.max);
    }
}

glm::dvec3 rotationVector(const glm::dmat3& r)
{
    // r - r^T = 2 sin(angle) [axis]x; element (row i, column j) is r[j][i] in GLM.
    const glm::dvec3 w(0.5 * (r[1][2] - r[2][1]), 0.5 * (r[2][0] - r[0][2]), 0.5 * (r[0][1] - r[1][0]));
    const double sine = glm::length(w);
    const double cosine = 0.5 * (r[0][0] + r[1][1] + r[2][2] - 1.0);
    const double angle = std::atan2(sine, cosine);
    if (cosine < 0.0 && sine < 1e-3)
    {
        // Near a half turn the antisymmetric part vanishes; the axis is the largest column of (r + I) / 2 = a a^T.
        unsigned j = 0;
        for (unsigned i = 1; i < 3; ++i)
            if (r[i][i] > r[j][j]) j = i;
        glm::dvec3 axis = r[j];
        axis[j] += 1.0;
        axis = glm::normalize(axis);
        if (glm::dot(axis, w) < 0.0) axis = -axis;
        return axis * angle;
    }
    if (sine < 1e-12) return w; // angle ~ sine
    return w * (angle / sine);
}

glm::dmat3 shortestArc(const glm::dvec3& from, const glm::dvec3& to)
{
    const glm::dvec3 f = glm::normalize(from), t = glm::normalize(to);
    glm::dvec3 axis = glm::cross(f, t);
    const double sine = glm::length(axis);
    const double cosine = glm::dot(f, t);
    if (sine < 1e-12)
    {
        if (cosine > 0.0) return glm::dmat3(1.0);
        // Half a turn about any axis perpendicular to f.
        axis = glm::cross(f, std::abs(f.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0));
    }
    return glm::mat3_cast(glm::angleAxis(std::atan2(sine, cosine), glm::normalize(axis)));
}

glm::dvec3 rotateAbout(const glm::dvec3& v, const glm::dvec3& a, double angle)
{
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    return v * c + glm::cross(a, v) * s + a * (glm::dot(a, v) * (1.0 - c));
}

double angleAbout(const glm::dvec3& a, const glm::dvec3& from, const glm::dvec3& to)
{
    const glm::dvec3 f = from - a * glm::dot(a, from);
    const glm::dvec3 t = to - a * glm::dot(a, to);
    if (glm::dot(f, f) < 1e-24 || glm::dot(t, t) < 1e-24) return 0.0;
    return std::atan2(glm::dot(a, glm::cross(f, t)), glm::dot(f, t));
}

void decomposeEuler(const glm::dmat3& r, const std::uint8_t axes[3], double first[3], double second[3])
{
    const unsigned i = axes[0], j = axes[1], k = axes[2];
    // +1 for the cyclic orders (XYZ, YZX, ZXY), -1 for the others.
    const double parity = j == (i + 1) % 3 ? 1.0 : -1.0;
    auto m = [&r](unsigned row, unsigned column) { return r[column][row]; };
    const double cosMiddle = std::sqrt(m(i, i) * m(i, i) + m(i, j) * m(i, j));
    first[1] = arctangent2(parity * m(i, k), cosMiddle);
    if (cosMiddle > 1e-12)
    {
        first[0] = arctangent2(-parity * m(j, k), m(k, k));
        first[2] = arctangent2(-parity * m(i, j), m(i, i));
    }
    else
    {
        // Gimbal lock: only a0 +- a2 is defined; put it all in a2.
        first[0] = 0.0;
        first[2] = arctangent2(parity * m(j, i), m(j, j));
    }
    const double pi = glm::pi<double>();
    second[0] = first[0] + pi;
    second[1] = pi - first[1];
    second[2] = first[2] + pi;
}

double fitAngleToLimits(double angle, double min, double max, double reference)
{
    bool clamped;
    return fitAngleToLimits(angle, min, max, reference, clamped);
}

bool turnWithinLimitsByWholeTurns(double angle, double min, double max, double reference, double& turned)
{
    const double twoPi = 2.0 * glm::pi<double>();
    // Whole turns from angle to the reference, rounded (inline where |turns| < 2^52, as it always is in practice).
    const double turns = (reference - angle) * (1.0 / twoPi);
    const double roundedTurns = std::abs(turns) < 4503599627370496.0
                                    ? static_cast<double>(static_cast<std::int64_t>(turns + (turns < 0.0 ? -0.5 : 0.5)))
                                    : std::round(turns);
    const double nearest = angle + twoPi * roundedTurns;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int k = -2; k <= 2; ++k)
    {
        const double candidate = nearest + k * twoPi;
        if (candidate < min || candidate > max) continue;
        const double distance = std::abs(candidate - reference);
        if (distance < bestDistance)
        {
            turned = candidate;
            bestDistance = distance;
        }
    }
    return bestDistance < std::numeric_limits<double>::infinity();
}

double fitAngleToLimits(double angle, double min, double max, double reference, bool& clamped)
{
    double turned = angle;
    clamped = !turnWithinLimits(angle, min, max, reference, turned);
    if (!clamped) return turned;
    // No turn of the angle lies within the limits: the limit it is closest to, going round the circle.
    const double twoPi = 2.0 * glm::pi<double>();
    const double toMin = std::abs(std::remainder(angle - min, twoPi));
    const double toMax = std::abs(std::remainder(angle - max, twoPi));
    return toMin <= toMax ? min : max;
}

glm::dmat3 composeEuler(const JointKinematics& k, const double angles[3])
{
    glm::dmat3 m(1.0);
    for (unsigned r = 0; r < 3; ++r)
    {
        // m * R_axis: only the two columns other than the axis mix.
        const unsigned i = (k.rotationAxis[r] + 1u) % 3u, j = (k.rotationAxis[r] + 2u) % 3u;
        const double c = std::cos(angles[r]), s = std::sin(angles[r]);
        const glm::dvec3 ci = m[i], cj = m[j];
        m[i] = c * ci + s * cj;
        m[j] = -s * ci + c * cj;
    }
    return m;
}

bool fitJointRotation(const ActorDefinition& definition, const JointKinematics& k, const glm::dmat3& target,
                      const double* dofs, double angles[3])
{
    double solutions[2][3];
    decomposeEuler(target, k.rotationAxis, solutions[0], solutions[1]);
    double fitted[2][3];
    // Fits one solution to the limits; true when no angle had to be clamped (only turned by whole turns).
    auto fit = [&](unsigned s) {
        bool exact = true;
        for (unsigned r = 0; r < 3; ++r)
        {
            const unsigned dof = k.rotationDof[r];
            bool clamped;
            fitted[s][r] = fitAngleToLimits(solutions[s][r], definition.getDofMin(dof), definition.getDofMax(dof),
                                            dofs[dof], clamped);
            exact = exact && !clamped;
        }
        return exact;
    };
    unsigned chosen = 0;
    bool exact = fit(0);
    if (!exact)
    {
        exact = fit(1);
        if (exact) chosen = 1;
        else
        {
            auto norm2 = [](const glm::dmat3& m) {
                return glm::dot(m[0], m[0]) + glm::dot(m[1], m[1]) + glm::dot(m[2], m[2]);
            };
            chosen = norm2(composeEuler(k, fitted[1]) - target) < norm2(composeEuler(k, fitted[0]) - target) ? 1 : 0;
        }
    }
    for (unsigned r = 0; r < 3; ++r) angles[r] = fitted[chosen][r];
    return exact;
}

} // namespace osgActor
