#include <osgActor/mocap/MocapImport>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <cctype>

namespace osgActor {

const char* upAxisName(UpAxis axis) { return axis == UpAxis::Z ? "z" : "y"; }

bool parseUpAxis(const std::string& text, UpAxis& axis)
{
    if (text == "y") axis = UpAxis::Y;
    else if (text == "z") axis = UpAxis::Z;
    else return false;
    return true;
}

glm::dquat upAxisToZUp(UpAxis fileUpAxis)
{
    if (fileUpAxis == UpAxis::Z) return glm::dquat(1.0, 0.0, 0.0, 0.0);
    return glm::angleAxis(0.5 * glm::pi<double>(), glm::dvec3(1.0, 0.0, 0.0));
}

bool eulerOrderForAxes(const unsigned* axes, unsigned count, EulerOrder& order)
{
    for (unsigned o = 0; o < 6; ++o)
    {
        unsigned orderAxes[3];
        eulerOrderAxes(static_cast<EulerOrder>(o), orderAxes);
        unsigned matched = 0;
        for (unsigned k = 0; k < 3 && matched < count; ++k)
            if (orderAxes[k] == axes[matched]) ++matched;
        // Every given axis found, in order; with repeated axes a later one can never match.
        if (matched == count)
        {
            bool repeated = false;
            for (unsigned i = 0; i < count; ++i)
                for (unsigned j = i + 1; j < count; ++j) repeated = repeated || axes[i] == axes[j];
            if (repeated) return false;
            order = static_cast<EulerOrder>(o);
            return true;
        }
    }
    return false;
}

std::string baseNameOf(const std::string& path)
{
    const std::size_t slash = path.find_last_of("/\\");
    std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    const std::size_t dot = name.rfind('.');
    if (dot != std::string::npos && dot > 0) name.erase(dot);
    return name;
}

std::string lowerExtensionOf(const std::string& path)
{
    const std::size_t dot = path.find_last_of('.');
    const std::size_t slash = path.find_last_of("/\\");
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::string();
    std::string extension = path.substr(dot);
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return extension;
}

} // namespace osgActor
