#include "ActorControls.h"
#include "ClipControls.h"

#include <osg/Math>

#include <cstdio>
#include <sstream>

namespace osgActorViewer {

namespace {

const double kRotationStep = osg::DegreesToRadians(5.0); // radians per key press
const double kTranslationStep = 0.02;                    // fraction of the actor's bound radius per key press

struct KeyHelp
{
    const char* keys;
    const char* action;
};

const KeyHelp kKeys[] = {
    {"p", "play/pause"},
    {"< >", "speed"},
    {"n N", "next/previous clip"},
    {"Left Right", "scrub (pauses)"},
    {"a", "next actor"},
    {"j J", "next/previous joint"},
    {"d D", "next/previous DOF"},
    {"Up Down", "turn the DOF"},
    {"r", "reset the pose"},
    {"v", "hide/show the limb"},
    {"g", "IK goal on the joint (drag it)"},
    {"x", "joint axes"},
    {"k", "skeleton lines"},
    {"i", "this panel"},
    {"h", "all keys"},
};

} // namespace

ActorControls::ActorControls(const std::vector<osg::ref_ptr<osgActor::ActorNode>>& actors,
                             const std::vector<osg::ref_ptr<SkeletonOverlay>>& overlays, PlaybackClock& clock,
                             InfoPanel* panel)
    : _actors(actors), _overlays(overlays), _clock(clock), _panel(panel), _actor(0), _joint(0), _dofSlot(0),
      _showAxes(false), _showLines(false), _lastFrameTime(-1.0), _framesPerSecond(0.0)
{
    selectActor(0);
}

std::string ActorControls::keyList()
{
    // Three keys to a line, so that the list stays small on the screen.
    std::ostringstream text;
    unsigned column = 0;
    for (const KeyHelp& key : kKeys)
    {
        char entry[64];
        std::snprintf(entry, sizeof(entry), "%s: %s", key.keys, key.action);
        text << entry << (++column % 3 == 0 ? "\n" : "    ");
    }
    return text.str();
}

void ActorControls::getUsage(osg::ApplicationUsage& usage) const
{
    for (const KeyHelp& key : kKeys) usage.addKeyboardMouseBinding(key.keys, key.action);
}

osgActor::ActorNode* ActorControls::getSelectedActor() const
{
    return _actor < _actors.size() ? _actors[_actor].get() : nullptr;
}

int ActorControls::getSelectedDof() const
{
    const osgActor::ActorNode* actor = getSelectedActor();
    if (actor == nullptr || !actor->getDefinition() || _joint < 0) return -1;
    const osgActor::ActorDefinition& definition = *actor->getDefinition();
    const unsigned numDofs = definition.getNumJointDofs(unsigned(_joint));
    if (numDofs == 0) return -1;
    return int(definition.getFirstDof(unsigned(_joint)) + _dofSlot % numDofs);
}

bool ActorControls::handle(const osgGA::GUIEventAdapter& ea, osgGA::GUIActionAdapter&, osg::Object*,
                           osg::NodeVisitor*)
{
    switch (ea.getEventType())
    {
    case osgGA::GUIEventAdapter::FRAME:
    {
        const double now = ea.getTime();
        updatePanel(_lastFrameTime >= 0.0 ? now - _lastFrameTime : 0.0);
        _lastFrameTime = now;
        return false;
    }
    case osgGA::GUIEventAdapter::RESIZE:
        if (_panel) _panel->resize(ea.getWindowWidth(), ea.getWindowHeight());
        return false;
    case osgGA::GUIEventAdapter::KEYDOWN:
        return handleKey(ea.getKey());
    default:
        return false;
    }
}

bool ActorControls::handleKey(int key)
{
    switch (key)
    {
    case 'p': _clock.togglePlaying(); return true;
    case '>': _clock.setSpeed(_clock.getSpeed() * 2.0); return true;
    case '<': _clock.setSpeed(_clock.getSpeed() * 0.5); return true;
    case osgGA::GUIEventAdapter::KEY_Right: _clock.scrub(+1); return true;
    case osgGA::GUIEventAdapter::KEY_Left: _clock.scrub(-1); return true;
    case 'n':
    case 'N':
        if (osgActor::ActorNode* actor = getSelectedActor()) _message = switchClip(*actor, key == 'n' ? +1 : -1);
        return true;
    case 'a': selectActor(_actors.empty() ? 0 : (_actor + 1) % unsigned(_actors.size())); return true;
    case 'j': selectJoint(+1); return true;
    case 'J': selectJoint(-1); return true;
    case 'd': selectDof(+1); return true;
    case 'D': selectDof(-1); return true;
    case osgGA::GUIEventAdapter::KEY_Up: turnSelectedDof(+1); return true;
    case osgGA::GUIEventAdapter::KEY_Down: turnSelectedDof(-1); return true;
    case 'r':
        if (osgActor::ActorNode* actor = getSelectedActor()) actor->resetDofs();
        _message = "pose reset";
        return true;
    case 'v': toggleSelectedJointHidden(); return true;
    case 'g': toggleIkGoal(); return true;
    case 'x': _showAxes = !_showAxes; showOverlays(); return true;
    case 'k': _showLines = !_showLines; showOverlays(); return true;
    case 'i':
        if (_panel) _panel->setPanelVisible(!_panel->getPanelVisible());
        return true;
    default: return false;
    }
}

void ActorControls::selectActor(unsigned index)
{
    if (_ikGoal) _ikGoal->detach();
    _actor = index;
    _joint = getSelectedActor() && getSelectedActor()->getNumSkeletonNodes() > 0 ? 0 : -1;
    _dofSlot = 0;
    showOverlays();
}

void ActorControls::selectJoint(int step)
{
    const osgActor::ActorNode* actor = getSelectedActor();
    if (actor == nullptr || actor->getNumSkeletonNodes() == 0) return;
    const int numJoints = int(actor->getNumSkeletonNodes());
    _joint = ((_joint + step) % numJoints + numJoints) % numJoints;
    _dofSlot = 0;
    showOverlays();
}

void ActorControls::selectDof(int step)
{
    const osgActor::ActorNode* actor = getSelectedActor();
    if (actor == nullptr || _joint < 0) return;
    const int numDofs = int(actor->getDefinition()->getNumJointDofs(unsigned(_joint)));
    if (numDofs > 0) _dofSlot = unsigned(((int(_dofSlot) + step) % numDofs + numDofs) % numDofs);
}

void ActorControls::turnSelectedDof(int direction)
{
    osgActor::ActorNode* actor = getSelectedActor();
    const int dof = getSelectedDof();
    if (actor == nullptr || dof < 0)
    {
        _message = "this joint has no DOF to turn";
        return;
    }
    const bool rotation = osgActor::isRotation(actor->getDefinition()->getDofType(unsigned(dof)));
    const double step = rotation ? kRotationStep : kTranslationStep * actor->getBound().radius();
    const double wanted = actor->getDof(unsigned(dof)) + direction * step;
    actor->setDof(unsigned(dof), wanted);
    _message = actor->getDof(unsigned(dof)) != wanted ? "at the DOF's limit" : "";
}

void ActorControls::toggleSelectedJointHidden()
{
    osgActor::ActorNode* actor = getSelectedActor();
    if (actor == nullptr || _joint < 0) return;
    osgActor::SkeletonNode* node = actor->getSkeletonNode(unsigned(_joint));
    node->setHidden(!node->getHidden());
    _message = node->getName() + (node->getHidden() ? " hidden (still posed)" : " shown");
}

void ActorControls::toggleIkGoal()
{
    if (!_ikGoal)
    {
        _message = "IK goals are off in this viewer";
        return;
    }
    if (_ikGoal->isAttached())
    {
        _ikGoal->detach();
        _message = "IK goal removed";
        return;
    }
    osgActor::ActorNode* actor = getSelectedActor();
    _message = actor != nullptr && _joint >= 0 ? _ikGoal->attach(*actor, unsigned(_joint)) : "no joint selected";
}

void ActorControls::showOverlays()
{
    for (unsigned i = 0; i < _overlays.size(); ++i)
    {
        _overlays[i]->setShowAxes(_showAxes);
        _overlays[i]->setShowLines(_showLines);
        _overlays[i]->setSelectedJoint(i == _actor ? _joint : -1);
    }
}

void ActorControls::updatePanel(double frameSeconds)
{
    if (frameSeconds > 0.0)
    {
        const double instant = 1.0 / frameSeconds;
        _framesPerSecond = _framesPerSecond > 0.0 ? 0.9 * _framesPerSecond + 0.1 * instant : instant;
    }
    if (_panel) _panel->setStatus(statusText());
}

std::string ActorControls::statusText() const
{
    std::ostringstream text;
    text.setf(std::ios::fixed);
    text.precision(2);
    const osgActor::ActorNode* actor = getSelectedActor();
    if (actor == nullptr) text << "no actor in the scene\n";
    else
    {
        const osgActor::ActorDefinition& definition = *actor->getDefinition();
        text << "actor " << (_actor + 1) << "/" << _actors.size() << ": "
             << (actor->getName().empty() ? definition.getName() : actor->getName()) << "  ("
             << definition.getNumJoints() << " joints, " << definition.getNumDofs() << " DOFs)\n";
        if (_joint >= 0)
        {
            const osgActor::SkeletonNode* node = actor->getSkeletonNode(unsigned(_joint));
            text << "joint " << definition.getJointName(unsigned(_joint)) << (node->getHidden() ? " [hidden]" : "");
            const int dof = getSelectedDof();
            if (dof >= 0)
            {
                const double value = actor->getDof(unsigned(dof));
                const bool rotation = osgActor::isRotation(definition.getDofType(unsigned(dof)));
                text << "  " << definition.getDofName(unsigned(dof)) << " = "
                     << (rotation ? osg::RadiansToDegrees(value) : value) << (rotation ? " deg" : "");
            }
            else text << "  (no DOF)";
            text << "\n";
        }
        text << "clip: " << describeClip(*actor) << "\n";
    }
    text << "time " << _clock.getTime() << " s  x" << _clock.getSpeed()
         << (_clock.isPlaying() ? "  playing" : "  paused")
         << "\n";
    text.precision(0);
    text << _framesPerSecond << " frames/s\n";
    if (!_message.empty()) text << _message << "\n";
    return text.str();
}

} // namespace osgActorViewer
