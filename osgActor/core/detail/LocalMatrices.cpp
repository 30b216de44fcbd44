#include <osgActor/core/detail/LocalMatrices>

#include <algorithm>
#include <cstring>

namespace osgActor {

LocalMatrices::LocalMatrices(unsigned numJoints) : _own(numJoints, glm::dmat4(1.0)), _targets(numJoints)
{
    for (unsigned j = 0; j < numJoints; ++j) _targets[j] = &_own[j][0][0];
}

LocalMatrices::LocalMatrices(const LocalMatrices& other) : LocalMatrices(other.size())
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

bool LocalMatrices::redirect(const std::vector<double*>& targets)
{
    if (targets.size() != _targets.size() ||
        std::any_of(targets.begin(), targets.end(), [](const double* t) { return t == nullptr; }))
        return false;
    for (unsigned j = 0; j < size(); ++j)
        if (targets[j] != _targets[j]) std::memcpy(targets[j], _targets[j], sizeof(glm::dmat4));
    _targets = targets;
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
