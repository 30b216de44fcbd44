#include <osgActor/core/retarget/FootContacts>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace osgActor {

std::vector<FootContact> findFootContacts(Span<const glm::dvec3> positions, double frameRate, double hipHeight,
                                          const FootContactOptions& options)
{
    std::vector<FootContact> contacts;
    const std::size_t n = positions.size();
    if (n == 0 || !(frameRate > 0.0)) return contacts;
    const double height = options.height >= 0.0 ? options.height : 0.06 * hipHeight;
    const double speed = options.speed >= 0.0 ? options.speed : 0.1 * hipHeight;
    const unsigned minFrames =
        std::max(1u, static_cast<unsigned>(std::ceil(std::max(0.0, options.minDuration) * frameRate - 1e-9)));

    double lowest = positions[0].z;
    for (const glm::dvec3& p : positions) lowest = std::min(lowest, p.z);

    auto planted = [&](std::size_t f) {
        if (positions[f].z > lowest + height) return false;
        if (n == 1) return true;
        const std::size_t before = f > 0 ? f - 1 : f, after = f + 1 < n ? f + 1 : f;
        const double seconds = static_cast<double>(after - before) / frameRate;
        return glm::length(positions[after] - positions[before]) <= speed * seconds;
    };
    for (std::size_t f = 0; f < n;)
    {
        if (!planted(f))
        {
            ++f;
            continue;
        }
        std::size_t last = f;
        while (last + 1 < n && planted(last + 1)) ++last;
        if (last - f + 1 >= minFrames)
            contacts.push_back(FootContact{static_cast<unsigned>(f), static_cast<unsigned>(last)});
        f = last + 1;
    }
    return contacts;
}

double footHoldWeight(unsigned frame, const FootContact& contact, double blendFrames)
{
    if (frame >= contact.first && frame <= contact.last) return 1.0;
    const double away = frame < contact.first ? contact.first - frame : frame - contact.last;
    if (!(blendFrames > 0.0) || away >= blendFrames) return 0.0;
    const double x = 1.0 - away / blendFrames;
    return x * x * (3.0 - 2.0 * x);
}

} // namespace osgActor
