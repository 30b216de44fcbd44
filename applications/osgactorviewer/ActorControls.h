/* osgactorviewer: the viewer's own keys (playback, joint selection, direct kinematics, hide, overlays, panel). */
#ifndef OSGACTORVIEWER_ACTORCONTROLS_H
#define OSGACTORVIEWER_ACTORCONTROLS_H 1

#include "IkGoalDragger.h"
#include "InfoPanel.h"
#include "PlaybackClock.h"
#include "SkeletonOverlay.h"

#include <osgActor/ActorNode>

#include <osgGA/GUIEventHandler>

#include <memory>
#include <string>
#include <vector>

namespace osgActorViewer {

/** Handles the keys of osgactorviewer and keeps the panel current. The actors come from the loaded scene; the
  * selection is one actor, one of its joints and one of that joint's DOFs. Turning a DOF writes it with
  * ActorNode::setDof (direct kinematics: limits apply, and a controller driving the same DOF takes it back). */
class ActorControls : public osgGA::GUIEventHandler
{
public:
    ActorControls(const std::vector<osg::ref_ptr<osgActor::ActorNode>>& actors,
                  const std::vector<osg::ref_ptr<SkeletonOverlay>>& overlays, PlaybackClock& clock, InfoPanel* panel);

    bool handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter& aa, osg::Object*,
                osg::NodeVisitor*) override;
    void getUsage(osg::ApplicationUsage& usage) const override;

    /** Where 'g' puts IK goals; without one, 'g' says that IK dragging is off. */
    void setIkGoalDragger(const std::shared_ptr<IkGoalDragger>& dragger) { _ikGoal = dragger; }

    /** One line per key, as the panel lists them. */
    static std::string keyList();

    /** The selected actor, or null when the scene has none. */
    osgActor::ActorNode* getSelectedActor() const;
    int getSelectedJoint() const { return _joint; }
    /** The selected DOF's index in the actor's DOF vector, or -1 if the joint has none. */
    int getSelectedDof() const;

protected:
    ~ActorControls() override = default;

    bool handleKey(int key);
    void selectActor(unsigned index);
    void selectJoint(int step);
    void selectDof(int step);
    void turnSelectedDof(int direction);
    void toggleSelectedJointHidden();
    void toggleIkGoal();
    void showOverlays();
    void updatePanel(double frameSeconds);
    std::string statusText() const;

    std::vector<osg::ref_ptr<osgActor::ActorNode>> _actors;
    std::vector<osg::ref_ptr<SkeletonOverlay>> _overlays; // one per actor, same order
    PlaybackClock& _clock;
    osg::ref_ptr<InfoPanel> _panel;
    std::shared_ptr<IkGoalDragger> _ikGoal;
    unsigned _actor;
    int _joint;        // index in the selected actor's definition
    unsigned _dofSlot; // which of the joint's DOFs
    bool _showAxes;
    bool _showLines;
    double _lastFrameTime;  // reference time of the previous frame, seconds (negative before the first)
    double _framesPerSecond; // smoothed
    std::string _message;   // the result of the last action, shown on the panel
};

} // namespace osgActorViewer

#endif
