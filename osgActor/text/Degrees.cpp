#include <osgActor/text/Degrees>
#include <osgActor/text/Numbers>

namespace osgActor {

std::string formatDegrees(double radians)
{
    return formatInverse(radians, radians * kDegreesPerRadian, radiansFromDegrees);
}

} // namespace osgActor
