// Internal to the library (not installed, NOT API): per-frame work that follows one actor's pose and touches only
// its own per-actor state (a skinned mesh's skinning matrices and bound for that actor), run by ActorGroup on the
// worker thread that updated the actor, right after the actor's own update, rather than serially in OSG's update
// traversal.
//
// The update traversal still visits what it visited (the skinned mesh requires it) and stays in charge: a follower
// is put on its actor's list by the update thread when the traversal meets it (follow()), and at the next frame the
// worker runs it only if that traversal met it at the frame before; one that was not met is dropped from the list.
// What the traversal then finds done for this frame, with the pose unchanged since, it does not do again; what must
// be done on the update thread (dirtying bounds that parents share) it still does.
#ifndef OSGACTOR_DETAIL_POSEFOLLOWER_H
#define OSGACTOR_DETAIL_POSEFOLLOWER_H 1

#include <osgActor/ActorNode>

#include <osg/Referenced>

namespace osgActor {
namespace detail {

class PoseFollower : public osg::Referenced
{
public:
    /** On the actor's worker, after its update claimed the frame: the pose has no dirty joint and its model
      * matrices are current. Does the frame's work for that actor, touching this object's own state only. */
    virtual void followPose(const ActorNode& actor, unsigned frameNumber) = 0;

    /** The update thread, when its traversal meets the follower for the actor at a frame: put on the actor's list
      * (once), so that the actor's worker runs it from the next frame on. */
    static void follow(ActorNode& actor, PoseFollower& follower, unsigned frameNumber);

protected:
    ~PoseFollower() override = default;

private:
    friend class osgActor::ActorNode;
    bool _listed = false;          // on its actor's list
    unsigned _lastMetFrame = 0;    // the last frame the update traversal met it
};

} // namespace detail
} // namespace osgActor

#endif
