#include <osgActor/core/Clip>

namespace osgActor {

namespace {

Clip::Kernel kernelOf(const ClipChannel& channel)
{
    switch (channel.interpolation)
    {
    case Interpolation::Step: return Clip::Kernel::Step;
    case Interpolation::Linear: return channel.angular ? Clip::Kernel::LinearAngular : Clip::Kernel::Linear;
    case Interpolation::Cubic: return channel.angular ? Clip::Kernel::CubicAngular : Clip::Kernel::Cubic;
    }
    return Clip::Kernel::Linear;
}

} // namespace

int Clip::findChannel(const std::string& target) const
{
    for (unsigned c = 0; c < _channels.size(); ++c)
        if (_channels[c].target == target) return static_cast<int>(c);
    return -1;
}

void Clip::setChannels(const std::vector<ClipChannel>& channels)
{
    _channels = channels;
    _kernels.clear();
    _angularMask.clear();
    _nonLinearBefore.assign(1, 0u);
    for (const ClipChannel& channel : _channels)
    {
        const Kernel kernel = kernelOf(channel);
        _kernels.push_back(kernel);
        _angularMask.push_back(kernel == Kernel::LinearAngular ? 1.0 : 0.0);
        const bool linear = kernel == Kernel::Linear || kernel == Kernel::LinearAngular;
        _nonLinearBefore.push_back(_nonLinearBefore.back() + (linear ? 0u : 1u));
    }
}

void Clip::initCursor(ClipCursor& cursor) const { cursor.keys.assign(_uniform ? 0 : _channels.size(), 0u); }

} // namespace osgActor
