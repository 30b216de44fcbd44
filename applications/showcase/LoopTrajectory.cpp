#include "LoopTrajectory.h"

#include <osgActor/GlmOsg>

#include <osg/Math>

#include <algorithm>
#include <cmath>
#include <vector>

namespace osgActorShowcase {

osgActor::TrajectoryBuildResult makeLoopTrajectory(const std::string& name,
                                                   const std::function<osg::Vec3d(double)>& curve, double speed,
                                                   double sampleSeconds)
{
    osgActor::TrajectoryBuildResult result;
    if (!(speed > 0.0) || !std::isfinite(speed) || !(sampleSeconds > 0.0) || !std::isfinite(sampleSeconds))
    {
        result.error = "trajectory '" + name + "': the speed and the time between keys must be positive";
        return result;
    }

    // Arc length along a fine sampling of the curve, then keys at equal steps of length.
    const int kSamples = 4000;
    std::vector<osg::Vec3d> points(kSamples + 1);
    std::vector<double> lengths(kSamples + 1, 0.0);
    for (int i = 0; i <= kSamples; ++i)
    {
        points[i] = curve(double(i) / kSamples);
        if (i > 0) lengths[i] = lengths[i - 1] + (points[i] - points[i - 1]).length();
    }
    const double total = lengths.back();
    if (!(total > 0.0) || !std::isfinite(total))
    {
        result.error = "trajectory '" + name + "': the curve has no length";
        return result;
    }
    const double duration = total / speed;

    const int numKeys = std::max(2, int(std::ceil(duration / sampleSeconds)));
    std::vector<osgActor::TrajectoryKey> keys(numKeys + 1);
    int i = 0;
    for (int k = 0; k <= numKeys; ++k)
    {
        const double wanted = total * k / numKeys;
        while (i < kSamples - 1 && lengths[i + 1] < wanted) ++i;
        const double f = (wanted - lengths[i]) / std::max(1e-12, lengths[i + 1] - lengths[i]);
        const osg::Vec3d direction = points[i + 1] - points[i];
        keys[k].time = duration * k / numKeys;
        keys[k].position = osgActor::toGlm(points[i] * (1.0 - f) + points[i + 1] * f);
        keys[k].heading = std::atan2(direction.y(), direction.x()) + osg::PI_2;
    }
    return osgActor::TrajectoryBuilder::build(name, std::move(keys));
}

} // namespace osgActorShowcase
