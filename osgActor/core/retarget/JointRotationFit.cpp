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

double nearestAngleAbout(const glm::dmat3& m, unsigned axis)
{
    const unsigned i = (axis + 1u) % 3u, j = (axis + 2u) % 3u;
    return arctangent2(m[i][j] - m[j][i], m[i][i] + m[j][j]);
}

/** The two angles (product order a0, a1, distinct axes) whose rotation R_a0 * R_a1 is nearest target (a rotation) in
  * least squares, in closed form. With q = q_a0(angle0) q_a1(angle1) and m target's quaternion (w, x, y, z),
  * trace(R^T target) = 4 (q . m)^2 - 1, and q . m = u^T B v with u = (cos, sin) of angle0 / 2, v the same of
  * angle1 / 2 and B = [[w, m_a1], [m_a0, sign m_a2]] (sign: e_a0 e_a1 = sign e_a2): the best u and v are B's first
  * singular vectors. Every quantity used is a product of two of m's components, each linear in target's elements,
  * so neither the quaternion nor a trigonometric function is needed before the final arctangents. */
void nearestTwoAxes(const glm::dmat3& target, unsigned a0, unsigned a1, double angles[2])
{
    const unsigned a2 = 3u - a0 - a1;
    const double sign = a1 == (a0 + 1u) % 3u ? 1.0 : -1.0;
    const auto at = [&](unsigned row, unsigned column) { return target[column][row]; };
    const double trace = at(0, 0) + at(1, 1) + at(2, 2);
    const auto squared = [&](unsigned i) { return 0.25 * (1.0 + 2.0 * at(i, i) - trace); }; // m_i^2
    const auto timesW = [&](unsigned i) {                                                    // w m_i
        const unsigned j = (i + 1u) % 3u, k = (i + 2u) % 3u;
        return 0.25 * (at(k, j) - at(j, k));
    };
    const auto product = [&](unsigned i, unsigned j) { return 0.25 * (at(i, j) + at(j, i)); }; // m_i m_j
    // B's elements a = w, b = m_a1, c = m_a0, d = sign m_a2, multiplied in pairs.
    const double aa = 0.25 * (1.0 + trace), bb = squared(a1), cc = squared(a0), dd = squared(a2);
    const double ab = timesW(a1), ac = timesW(a0), ad = sign * timesW(a2);
    const double bc = product(a0, a1), bd = sign * product(a1, a2), cd = sign * product(a0, a2);
    // v is the first eigenvector of B^T B = [[aa + cc, ab + cd], [ab + cd, bb + dd]], at half of angle1; where both
    // eigenvalues are equal every v does, and angle1 = 0 is taken (angle0 is then a0's alone).
    const double half = 0.5 * ((aa + cc) - (bb + dd)), offDiagonal = ab + cd;
    const double radius = std::sqrt(half * half + offDiagonal * offDiagonal);
    const double c1 = radius > 1e-15 ? half / radius : 1.0, s1 = radius > 1e-15 ? offDiagonal / radius : 0.0;
    // u = B v, at half of angle0: its cosine and sine go as u0^2 - u1^2 and 2 u0 u1, from v's squares
    // (cos^2 = (1 + c1) / 2, sin^2 = (1 - c1) / 2, 2 cos sin = s1).
    const double cosSquared = 0.5 * (1.0 + c1), sinSquared = 0.5 * (1.0 - c1);
    const double u0u0 = aa * cosSquared + ab * s1 + bb * sinSquared;
    const double u1u1 = cc * cosSquared + cd * s1 + dd * sinSquared;
    const double u0u1 = ac * cosSquared + 0.5 * (ad + bc) * s1 + bd * sinSquared;
    angles[0] = arctangent2(2.0 * u0u1, u0u0 - u1u1);
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
