#include <osgActor/core/ik/IkJob>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace osgActor {

void IkWorkspace::resize(const IkChain& chain)
{
    const unsigned numDofs = chain.getNumDofs();
    jointModel.assign(chain.getNumJoints(), glm::dmat4(1.0));
    axis.assign(numDofs, glm::dvec3(0.0));
    pivot.assign(numDofs, glm::dvec3(0.0));
    jacobianPosition.assign(numDofs, glm::dvec3(0.0));
    jacobianOrientation.assign(numDofs, glm::dvec3(0.0));
    savedDofs.assign(numDofs, 0.0);
    bestDofs.assign(numDofs, 0.0);
    trialDofs.assign(numDofs, 0.0);
    sweepStarts.assign(kSweepHistory * numDofs, 0.0);
    sweepEnds.assign(kSweepHistory * numDofs, 0.0);
    mixingColumns.assign((kSweepHistory - 1) * numDofs, 0.0);
    locked.assign(numDofs, 0);
    frozen.assign(numDofs, 0);
}

bool IkWorkspace::fits(const IkChain& chain) const
{
    const std::size_t numDofs = chain.getNumDofs();
    return jointModel.size() == chain.getNumJoints() && axis.size() == numDofs && pivot.size() == numDofs &&
           jacobianPosition.size() == numDofs && jacobianOrientation.size() == numDofs &&
           savedDofs.size() == numDofs && bestDofs.size() == numDofs && trialDofs.size() == numDofs &&
           sweepStarts.size() == kSweepHistory * numDofs && sweepEnds.size() == kSweepHistory * numDofs &&
           mixingColumns.size() == (kSweepHistory - 1) * numDofs &&
           locked.size() == numDofs && frozen.size() == numDofs;
}

bool IkJob::validateInputs() const
{
    if (!definition || !chain || !goal || !dofs || !workspace) return false;
    if (!chain->fitsLayout(definition->getNumJoints(), definition->getNumDofs())) return false;
    if (!workspace->fits(*chain) || !goal->isValid()) return false;
    // A double is NaN or infinite when its 11 exponent bits are all set, i.e. when they plus one carry into bit 11:
    // integer arithmetic ORed over every value, which needs no branch per value and vectorises.
    auto nonFinite = [](double value) {
        std::uint64_t bits;
        std::memcpy(&bits, &value, sizeof bits);
        return (((bits >> 52) & 0x7ffu) + 1u) >> 11;
    };
    std::uint64_t any = 0;
    const double* matrix = &rootParentModel[0][0];
    for (unsigned i = 0; i < 16; ++i) any |= nonFinite(matrix[i]);
    // The DOFs finite and within the range a pose can hold: beyond it the chain's matrices could overflow.
    for (const IkChainDof& d : chain->getDofs()) any |= !(std::abs(dofs[d.dof]) <= kMaxDofMagnitude) ? 1u : 0u;
    return any == 0;
}

} // namespace osgActor
