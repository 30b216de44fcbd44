/* osgactorviewer: joint axes and skeleton lines drawn over an actor. */
#ifndef OSGACTORVIEWER_SKELETONOVERLAY_H
#define OSGACTORVIEWER_SKELETONOVERLAY_H 1

#include <osgActor/ActorNode>

#include <osg/Geode>
#include <osg/Geometry>

namespace osgActorViewer {

/** Lines in world space over one actor, rebuilt in every update traversal from the actor's joint world matrices
  * (so they follow controllers and manipulators, and show hidden joints too): a line from each joint to its
  * parent, the X (red), Y (green) and Z (blue) axes of each joint, and longer axes on the selected joint. Drawn
  * unlit, over the geometry (no depth test). Put it anywhere in the scene outside the actor's transforms. */
class SkeletonOverlay : public osg::Geode
{
public:
    explicit SkeletonOverlay(osgActor::ActorNode* actor);

    void setShowAxes(bool show) { _showAxes = show; }
    bool getShowAxes() const { return _showAxes; }
    void setShowLines(bool show) { _showLines = show; }
    bool getShowLines() const { return _showLines; }
    /** The joint whose axes are always drawn, longer; -1 for none. */
    void setSelectedJoint(int joint) { _selectedJoint = joint; }

    /** Rebuilds the lines for the actor's current pose (called by the overlay's update callback). */
    void rebuild();

protected:
    ~SkeletonOverlay() override = default;

    void addAxes(const osg::Matrixd& joint, double length);

    osg::observer_ptr<osgActor::ActorNode> _actor;
    osg::ref_ptr<osg::Geometry> _geometry;
    osg::ref_ptr<osg::Vec3Array> _vertices;
    osg::ref_ptr<osg::Vec4Array> _colours;
    osg::ref_ptr<osg::DrawArrays> _lines;
    double _axisLength; // model units, from the actor's size
    bool _showAxes;
    bool _showLines;
    int _selectedJoint;
};

} // namespace osgActorViewer

#endif
