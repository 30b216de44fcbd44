/* osgActorShowcase: the base of the showcase's rigs, which give the actors of a group the controllers that move
 * them. */
#ifndef OSGACTORSHOWCASE_CONTROLLERRIG_H
#define OSGACTORSHOWCASE_CONTROLLERRIG_H 1

#include "Export.h"

#include <osgActor/ActorNode>

#include <osg/Callback>
#include <osg/observer_ptr>

#include <vector>

namespace osgActorShowcase {

/** An update callback for a group that holds actors. In each update traversal it looks for the ActorNodes below the
  * group (also inside ProxyNodes and transforms, not inside other actors) and gives each one that is not rigged yet
  * its controllers (rig()), once; then it passes the traversal on, so the actors' own update runs those
  * controllers in the same frame. From then on the actor moves by the library's controllers alone (players, IK),
  * which advance by the frame's delta time like any controller.
  *
  * Actors may arrive late (a ProxyNode or the database pager loads them), so the search runs every frame. An actor
  * is rigged when it has a controller named getRigControllerName(); one that rig() refused is left alone. */
class OSGACTORSHOWCASE_EXPORT ControllerRig : public osg::NodeCallback
{
public:
    ControllerRig() = default;
    ControllerRig(const ControllerRig& rig, const osg::CopyOp& copyop)
        : osg::Object(rig, copyop), osg::Callback(rig, copyop), osg::NodeCallback(rig, copyop)
    {
    }

    void operator()(osg::Node* node, osg::NodeVisitor* nv) override;

    /** The name of the first controller rig() adds, by which a rigged actor is recognised. */
    virtual const char* getRigControllerName() const = 0;
    /** Adds the controllers to one actor; false, with an OSG_WARN that says why, when the actor cannot take them. */
    virtual bool rig(osgActor::ActorNode& actor) const = 0;

protected:
    ~ControllerRig() override = default;

private:
    bool wasRefused(const osgActor::ActorNode& actor) const;

    std::vector<osg::observer_ptr<osgActor::ActorNode>> _refused;
};

} // namespace osgActorShowcase

#endif
