#include <osgActor/core/Dof>

#include <algorithm>
#include <cctype>

namespace osgActor {

namespace {

const char* const kDofNames[kNumDofTypes] = {"rx", "ry", "rz", "tx", "ty", "tz"};
const char* const kOrderNames[] = {"XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"};
constexpr unsigned kNumOrders = sizeof(kOrderNames) / sizeof(kOrderNames[0]);

std::string lowered(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
}

std::string uppered(std::string text)
{
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    return text;
}

/** Index of key in names (compared after normalize), or -1. */
template <class Normalize>
int findName(const std::string& text, const char* const* names, unsigned count, Normalize normalize)
{
    const std::string key = normalize(text);
    for (unsigned i = 0; i < count; ++i)
        if (key == names[i]) return static_cast<int>(i);
    return -1;
}

} // namespace

const char* dofName(Dof dof) { return kDofNames[static_cast<unsigned>(dof)]; }

bool parseDof(const std::string& text, Dof& dof)
{
    const int index = findName(text, kDofNames, kNumDofTypes, lowered);
    if (index >= 0) dof = static_cast<Dof>(index);
    return index >= 0;
}

const char* eulerOrderName(EulerOrder order) { return kOrderNames[static_cast<unsigned>(order)]; }

bool parseEulerOrder(const std::string& text, EulerOrder& order)
{
    const int index = findName(text, kOrderNames, kNumOrders, uppered);
    if (index >= 0) order = static_cast<EulerOrder>(index);
    return index >= 0;
}

void eulerOrderAxes(EulerOrder order, unsigned axes[3])
{
    const char* name = kOrderNames[static_cast<unsigned>(order)];
    for (unsigned i = 0; i < 3; ++i) axes[i] = static_cast<unsigned>(name[i] - 'X');
}

} // namespace osgActor
