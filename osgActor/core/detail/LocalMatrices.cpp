#include <osgActor/core/detail/LocalMatrices>

#include <algorithm>
#include <cstring>

namespace osgActor {

LocalMatrices::LocalMatrices(unsigned numJoints) : LocalMatrices(unwritten(numJoints))
{
    std::fill(_own.begin(), _own.end(), glm::dmat4(1.0));
}

LocalMatrices LocalMatrices::unwritten(unsigned numJoints)
{
    LocalMatrices matrices;
    matrices._own.resize(numJoints); // default-initialized (AlignedAllocator): not written
    matrices._targets.resize(numJoints);
    for (unsigned j = 0; j < numJoints; ++j) matrices._targets[j] = &matrices._own[j][0][0];
    return matrices;
}

LocalMatrices LocalMatrices::at(std::vector<double*> targets)
{
    LocalMatrices matrices;
    if (std::any_of(targets.begin(), targets.end(), [](const double* t) { return t == nullptr; })) return matrices;
    matrices._targets = std::move(targets);
    matrices._redirected = true;
    return matrices;
}

LocalMatrices::LocalMatrices(const LocalMatrices& other) : LocalMatrices(unwritten(other.size()))
{
    copyValuesFrom(other.targets());
}

LocalMatrices& LocalMatrices::operator=(const LocalMatrices& other)
{
    if (this != &other) *this = LocalMatrices(other);
    return *this;
}

glm::dmat4 LocalMatrices::get(unsigned joint) const
{
    glm::dmat4 m;
    std::memcpy(&m[0][0], _targets[joint], sizeof(glm::dmat4));
    return m;
}

bool LocalMatrices::redirect(std::vector<double*> targets, Values values)
{
    if (targets.size() != _targets.size() ||
        std::any_of(targets.begin(), targets.end(), [](const double* t) { return t == nullptr; }))
        return false;
    if (values == Values::Copy)
    {
        for (unsigned j = 0; j < size(); ++j)
            if (targets[j] != _targets[j]) std::memcpy(targets[j], _targets[j], sizeof(glm::dmat4));
    }
    _targets = std::move(targets);
    _redirected = true;
    decltype(_own)().swap(_own);
    return true;
}

void LocalMatrices::own()
{
    if (isOwn()) return;
    _own.resize(size());
    for (unsigned j = 0; j < size(); ++j) std::memcpy(&_own[j][0][0], _targets[j], sizeof(glm::dmat4));
    for (unsigned j = 0; j < size(); ++j) _targets[j] = &_own[j][0][0];
    _redirected = false;
}

void LocalMatrices::copyValuesFrom(const double* const* sources)
{
    for (unsigned j = 0; j < size(); ++j) std::memcpy(_targets[j], sources[j], sizeof(glm::dmat4));
}

} // namespace osgActor
