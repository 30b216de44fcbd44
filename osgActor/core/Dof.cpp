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

} // namespace

const char* dofName(Dof dof) { return kDofNames[static_cast<unsigned>(dof)]; }

bool parseDof(const std::string& text, Dof& dof)
{
    const std::string key = lowered(text);
    for (unsigned i = 0; i < kNumDofTypes; ++i)
    {
        if (key == kDofNames[i])
        {
            dof = static_cast<Dof>(i);
            return true;
        }
    }
    return false;
}

const char* eulerOrderName(EulerOrder order) { return kOrderNames[static_cast<unsigned>(order)]; }

bool parseEulerOrder(const std::string& text, EulerOrder& order)
{
    const std::string key = uppered(text);
    for (unsigned i = 0; i < kNumOrders; ++i)
    {
        if (key == kOrderNames[i])
        {
            order = static_cast<EulerOrder>(i);
            return true;
        }
    }
    return false;
}

void eulerOrderAxes(EulerOrder order, unsigned axes[3])
{
    const char* name = kOrderNames[static_cast<unsigned>(order)];
    for (unsigned i = 0; i < 3; ++i) axes[i] = static_cast<unsigned>(name[i] - 'X');
}

} // namespace osgActor
