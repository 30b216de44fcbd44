/* osgactorviewer: an IK goal the user drags with an osgManipulator dragger, and the chain that follows it. */
#ifndef OSGACTORVIEWER_IKGOALDRAGGER_H
#define OSGACTORVIEWER_IKGOALDRAGGER_H 1

#include <osgActor/ActorNode>
#include <osgActor/IkNodeController>

#include <osg/Group>
#include <osg/MatrixTransform>
#include <osgManipulator/TranslateAxisDragger>

#include <memory>
#include <string>

namespace osgActorViewer {

/** Puts an IK goal on a joint: a marker at the joint's position that a TranslateAxisDragger moves (drag its arrows),
  * and an IkNodeController on the actor whose goal follows the marker, so the chain follows the drag. The chain is
  * one of the actor's own (its effector is the joint) when it has one, else a DLS chain from the joint's
  * grandparent (or the highest ancestor there is) to the joint. Everything it adds goes below a group of the
  * viewer's scene, outside the actor, and goes away with detach(). */
class IkGoalDragger
{
public:
    /** The group the dragger and the marker go below (in world space). */
    explicit IkGoalDragger(osg::Group* parent);
    ~IkGoalDragger();

    /** Starts dragging a goal for the joint; returns what happened, for the panel. Detaches any previous goal. */
    std::string attach(osgActor::ActorNode& actor, unsigned joint);
    /** Removes the dragger, the marker and the controller. */
    void detach();
    bool isAttached() const { return _controller != nullptr; }

    /** The node whose world matrix is the goal (the dragger moves it); null when detached. */
    osg::MatrixTransform* getGoalNode() { return _goal.get(); }
    const std::shared_ptr<osgActor::IkNodeController>& getController() const { return _controller; }

private:
    osg::ref_ptr<osg::Group> _parent;
    osg::ref_ptr<osg::Group> _handle; // dragger and marker
    osg::ref_ptr<osg::MatrixTransform> _goal;
    osg::ref_ptr<osgManipulator::TranslateAxisDragger> _dragger;
    osg::observer_ptr<osgActor::ActorNode> _actor;
    std::shared_ptr<osgActor::IkNodeController> _controller;
};

} // namespace osgActorViewer

#endif
