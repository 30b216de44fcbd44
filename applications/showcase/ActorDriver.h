/* osgActorShowcase: the base of the showcase's motion drivers. */
#ifndef OSGACTORSHOWCASE_ACTORDRIVER_H
#define OSGACTORSHOWCASE_ACTORDRIVER_H 1

#include "Export.h"

#include <osgActor/ActorNode>

#include <osg/Callback>

namespace osgActorShowcase {

/** An update callback for a group that holds actors: in each update traversal it drives every ActorNode below the
  * group (also inside ProxyNodes and transforms, not inside other actors) at the frame stamp's simulation time,
  * before the traversal reaches them (so that their own update computes the pose driven this frame), then passes
  * the traversal on.
  *
  * Drivers are functions of time only, with no state carried from frame to frame: rendering frame 100 alone gives
  * the same image as rendering frames 0..100, and scrubbing backwards works. */
class OSGACTORSHOWCASE_EXPORT ActorDriver : public osg::NodeCallback
{
public:
    ActorDriver() = default;
    ActorDriver(const ActorDriver& driver, const osg::CopyOp& copyop)
        : osg::Object(driver, copyop), osg::Callback(driver, copyop), osg::NodeCallback(driver, copyop)
    {
    }

    void operator()(osg::Node* node, osg::NodeVisitor* nv) override;

    /** Poses one actor for the given simulation time (seconds). */
    virtual void drive(osgActor::ActorNode& actor, double time) = 0;

protected:
    ~ActorDriver() override = default;
};

} // namespace osgActorShowcase

#endif
