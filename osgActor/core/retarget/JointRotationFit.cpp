#include <osgActor/core/retarget/JointRotationFit>
#include <osgActor/core/ik/Arctangent>
#include <osgActor/core/ik/IkKinematics>

#include <array>
#include <cmath>
#include <utility>

namespace osgActor {

namespace {

/** offset * R_A0 * R_A1 * R_A2, the first N of them, for one rotation sequence. */
template <unsigned N, unsigned A0, unsigned A1, unsigned A2>
glm::dmat3 rotationOfSequence(const glm::dmat3& offset, const JointKinematics& k, const double* c, const double* s)
{
    glm::dmat3 m = offset;
    if constexpr (N > 0) postRotateColumns<(A0 + 1) % 3, (A0 + 2) % 3>(m, c[k.rotationDof[0]], s[k.rotationDof[0]]);
    if constexpr (N > 1) postRotateColumns<(A1 + 1) % 3, (A1 + 2) % 3>(m, c[k.rotationDof[1]], s[k.rotationDof[1]]);
    if constexpr (N > 2) postRotateColumns<(A2 + 1) % 3, (A2 + 2) % 3>(m, c[k.rotationDof[2]], s[k.rotationDof[2]]);
    return m;
}

using RotationOfSequence = glm::dmat3 (*)(const glm::dmat3&, const JointKinematics&, const double*, const double*);

/** The function of rotation sequence Q (rotationSequenceOf's numbering: none, 3 single axes, 9 pairs, 27 triples). */
template <unsigned Q>
constexpr RotationOfSequence sequenceFunction()
{
    if constexpr (Q == 0)
        return &rotationOfSequence<0, 0, 0, 0>;
    else if constexpr (Q < 4)
        return &rotationOfSequence<1, Q - 1, 0, 0>;
    else if constexpr (Q < 13)
        return &rotationOfSequence<2, (Q - 4) / 3, (Q - 4) % 3, 0>;
    else
        return &rotationOfSequence<3, (Q - 13) / 9, ((Q - 13) / 3) % 3, (Q - 13) % 3>;
}

template <std::size_t... Q>
constexpr std::array<RotationOfSequence, sizeof...(Q)> sequenceTable(std::index_sequence<Q...>)
{
    return {sequenceFunction<Q>()...};
}

constexpr std::array<RotationOfSequence, kNumRotationSequences> kSequences =
    sequenceTable(std::make_index_sequence<kNumRotationSequences>());

} // namespace

glm::dmat3 jointRotation(const glm::dmat3& offset, const JointKinematics& k, const double* cosines,
                         const double* sines)
{
    return kSequences[k.rotationSequence](offset, k, cosines, sines);
}

glm::dmat3 jointRotation(const JointKinematics& k, const double* dofs)
{
    glm::dmat3 m(1.0);
    for (unsigned r = 0; r < k.numRotations; ++r)
    {
        const double angle = dofs[k.rotationDof[r]];
        postRotateAxis(m, k.rotationAxis[r], std::cos(angle), std::sin(angle));
    }
    return m;
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTwoPi = 2.0 * kPi;

/** The cosine and sine of the angle of the rotation about axis nearest m in the least-squares sense (the angle that
  * maximises the trace of R_axis(angle)^T m): from the 2x2 block of m the axis rotation mixes, sin from its skew part
  * and cos from its diagonal (m[column][row]). False where the block has no rotation in it. */
bool nearestCosSinAbout(const glm::dmat3& m, unsigned axis, double& c, double& s)
{
    const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
    s = m[i][j] - m[j][i];
    c = m[i][i] + m[j][j];
    const double r = std::sqrt(c * c + s * s);
    if (!(r > 1e-300)) return false;
    const double inverse = 1.0 / r;
    c *= inverse;
    s *= inverse;
    return true;
}

double nearestAngleAbout(const glm::dmat3& m, unsigned axis)
{
    const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
    return arctangent2(m[i][j] - m[j][i], m[i][i] + m[j][j]);
}

/** R_axis(angle)^T * m from the angle's cosine and sine: the transpose mixes two rows. */
glm::dmat3 preRotateTransposed(const glm::dmat3& m, unsigned axis, double c, double s)
{
    const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
    glm::dmat3 r = m;
    for (unsigned col = 0; col < 3; ++col)
    {
        r[col][i] = c * m[col][i] + s * m[col][j];
        r[col][j] = -s * m[col][i] + c * m[col][j];
    }
    return r;
}

/** The two angles (product order a0, a1) whose rotation R_a0 * R_a1 is nearest target: rounds of coordinate descent,
  * each half a closed-form step on cosines and sines (no trigonometric call), from the angle of a0 alone. */
void nearestTwoAxes(const glm::dmat3& target, unsigned a0, unsigned a1, double angles[2])
{
    double c0 = 1.0, s0 = 0.0, c1 = 1.0, s1 = 0.0;
    nearestCosSinAbout(target, a0, c0, s0);
    for (unsigned round = 0; round < 6; ++round)
    {
        // a1's best under a0, then a0's best under a1, until a0 stops moving.
        if (!nearestCosSinAbout(preRotateTransposed(target, a0, c0, s0), a1, c1, s1)) break;
        glm::dmat3 m = target;
        postRotateAxis(m, a1, c1, -s1); // target * R_a1^T
        const double previousC = c0, previousS = s0;
        if (!nearestCosSinAbout(m, a0, c0, s0)) break;
        if (std::abs(c0 - previousC) + std::abs(s0 - previousS) < 1e-10) break;
    }
    angles[0] = arctangent2(s0, c0);
    angles[1] = arctangent2(s1, c1);
}

double squaredDistance(const glm::dmat3& a, const glm::dmat3& b)
{
    const glm::dmat3 d = a - b;
    return glm::dot(d[0], d[0]) + glm::dot(d[1], d[1]) + glm::dot(d[2], d[2]);
}

} // namespace

bool fitJointRotationDofs(const ActorDefinition& definition, unsigned joint, const glm::dmat3& target, double* dofs)
{
    const JointKinematics& k = definition.getKinematics(joint);
    const unsigned n = k.numRotations;
    if (n == 0) return true;

    // Up to two candidate solutions, in product order.
    double candidates[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    unsigned numCandidates = 2;
    if (n == 3)
        decomposeEuler(target, k.rotationAxis, candidates[0], candidates[1]);
    else if (n == 2)
    {
        nearestTwoAxes(target, k.rotationAxis[0], k.rotationAxis[1], candidates[0]);
        numCandidates = 1;
    }
    else
    {
        candidates[0][0] = nearestAngleAbout(target, k.rotationAxis[0]);
        numCandidates = 1;
    }

    // Each candidate turned (and if need be clamped) into the limits, nearest the reference values.
    double fitted[2][3];
    bool clamped[2] = {false, false};
    double distance[2] = {0.0, 0.0};
    auto fit = [&](unsigned c) {
        for (unsigned r = 0; r < n; ++r)
        {
            const unsigned dof = k.rotationDof[r];
            const double min = definition.getDofRangeMin(dof), max = definition.getDofRangeMax(dof);
            const double angle = candidates[c][r], reference = dofs[dof];
            if (min <= -kMaxDofMagnitude && max >= kMaxDofMagnitude && std::abs(reference) < 1e9)
                // No limits: the whole turn nearest the reference, in closed form.
                fitted[c][r] = angle + kTwoPi * std::nearbyint((reference - angle) * (1.0 / kTwoPi));
            else if (!turnWithinLimits(angle, min, max, reference, fitted[c][r]))
            {
                fitted[c][r] = fitAngleToLimits(angle, min, max, reference);
                clamped[c] = true;
            }
            distance[c] += std::abs(fitted[c][r] - reference);
        }
    };
    fit(0);
    // The second solution turns the first and last angles by half a turn each: it is farther from the reference
    // whenever the first is within a quarter turn of it in all (2 pi - pi / 2 against pi / 2).
    if (numCandidates == 2 && !clamped[0] && distance[0] < 0.5 * kPi) numCandidates = 1;
    if (numCandidates == 2) fit(1);
    unsigned chosen = 0;
    if (numCandidates == 2)
    {
        if (clamped[0] != clamped[1])
            chosen = clamped[0] ? 1 : 0;
        else if (!clamped[0])
            chosen = distance[1] < distance[0] ? 1 : 0;
        else
        {
            // Both clamped: the one whose rotation is nearer the target.
            auto rotationOf = [&](unsigned c) {
                glm::dmat3 m(1.0);
                for (unsigned r = 0; r < n; ++r)
                    postRotateAxis(m, k.rotationAxis[r], std::cos(fitted[c][r]), std::sin(fitted[c][r]));
                return m;
            };
            const double d0 = squaredDistance(rotationOf(0), target), d1 = squaredDistance(rotationOf(1), target);
            chosen = d1 < d0 - 1e-15 || (std::abs(d1 - d0) <= 1e-15 && distance[1] < distance[0]) ? 1 : 0;
        }
    }
    for (unsigned r = 0; r < n; ++r) dofs[k.rotationDof[r]] = fitted[chosen][r];
    return n == 3 && !clamped[chosen];
}

} // namespace osgActor
