#include <osgActor/detail/PoseFollower.h>

namespace osgActor {
namespace detail {

void PoseFollower::follow(ActorNode& actor, PoseFollower& follower, unsigned frameNumber)
{
    follower._lastMetFrame = frameNumber;
    if (follower._listed) return;
    actor._poseFollowers.push_back(&follower);
    follower._listed = true;
}

} // namespace detail
} // namespace osgActor
