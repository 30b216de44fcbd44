#include <osgActor/core/ik/IkJob>

#include <cmath>

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
    locked.assign(numDofs, 0);
    frozen.assign(numDofs, 0);
}

bool IkWorkspace::fits(const IkChain& chain) const
{
    const std::size_t numDofs = chain.getNumDofs();
    return jointModel.size() == chain.getNumJoints() && axis.size() == numDofs && pivot.size() == numDofs &&
           jacobianPosition.size() == numDofs && jacobianOrientation.size() == numDofs &&
           savedDofs.size() == numDofs && bestDofs.size() == numDofs && locked.size() == numDofs && frozen.size() == numDofs;
}

bool IkJob::validateInputs() const
{
    if (!definition || !chain || !goal || !dofs || !workspace) return false;
    if (!chain->fitsLayout(definition->getNumJoints(), definition->getNumDofs())) return false;
    if (!workspace->fits(*chain) || !goal->isValid()) return false;
    for (unsigned c = 0; c < 4; ++c)
        for (unsigned r = 0; r < 4; ++r)
            if (!std::isfinite(rootParentModel[c][r])) return false;
    // Finite and within the range a pose can hold: beyond it the chain's matrices could overflow.
    for (const IkChainDof& d : chain->getDofs())
        if (!(std::abs(dofs[d.dof]) <= kMaxDofMagnitude)) return false;
    return true;
}

} // namespace osgActor
