#include <osgActor/core/ClipLibrary>

namespace osgActor {

bool ClipLibrary::addClip(ClipPtr clip)
{
    if (!clip || clip->getName().empty()) return false;
    const std::string name = clip->getName();
    _clips[name] = std::move(clip);
    return true;
}

ClipPtr ClipLibrary::getClip(const std::string& name) const
{
    const auto found = _clips.find(name);
    return found == _clips.end() ? ClipPtr() : found->second;
}

std::vector<std::string> ClipLibrary::getClipNames() const
{
    std::vector<std::string> names;
    for (const auto& entry : _clips) names.push_back(entry.first);
    return names;
}

} // namespace osgActor
