/* osgActorShowcase: stored paths once round a closed curve, for the library's TrajectoryPlayer. */
#ifndef OSGACTORSHOWCASE_LOOPTRAJECTORY_H
#define OSGACTORSHOWCASE_LOOPTRAJECTORY_H 1

#include "Export.h"

#include <osgActor/core/Trajectory>

#include <osg/Vec3d>

#include <functional>
#include <string>

namespace osgActorShowcase {

/** A trajectory once round a closed curve (curve(0) == curve(1)) at a constant speed (model units per second),
  * starting at time 0 with a key every sampleSeconds or a little less (equal steps of arc length), each key's
  * heading turned so that an actor facing -Y in its own frame faces the way of travel (heading = direction of
  * travel + 90 degrees, since a heading of 0 leaves the actor's -Y on -Y). Play it in PlayMode::Loop. Refuses (and
  * says why) a speed or sample time that is not positive and finite, and a curve that does not move. */
OSGACTORSHOWCASE_EXPORT osgActor::TrajectoryBuildResult makeLoopTrajectory(
    const std::string& name, const std::function<osg::Vec3d(double)>& curve, double speed, double sampleSeconds = 0.1);

} // namespace osgActorShowcase

#endif
