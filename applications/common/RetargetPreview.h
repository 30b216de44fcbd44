/* Shared by osgactorviewer and osgactorrender: a motion shown on its own skeleton beside an actor it is retargeted
 * onto (--retarget-preview, issue 27). */
#ifndef OSGACTORAPPS_RETARGETPREVIEW_H
#define OSGACTORAPPS_RETARGETPREVIEW_H 1

#include <osg/Node>

#include <string>

namespace osgActorApps {

/** The scene with a retargeting preview: the scene's first actor plays the motion of motionFile (a BVH file, or an
  * ASF file with its AMC beside it, as readMocapActor() finds it) retargeted onto it, with the IK pass (its clip
  * players give way to one that plays it in a loop), and beside it the motion's own skeleton plays it as a stick
  * figure, scaled to the actor's size (the retargeting's hip-height ratio) and turned to face the same way. Null, with
  * a message, when the scene has no actor, the motion cannot be read or the two cannot be retargeted. */
osg::ref_ptr<osg::Node> makeRetargetPreview(osg::Node& scene, const std::string& motionFile, std::string& error);

} // namespace osgActorApps

#endif
