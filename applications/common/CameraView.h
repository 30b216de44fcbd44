/* Shared by the applications: where the camera stands, and how to frame a scene automatically. */
#ifndef OSGACTORAPPS_CAMERAVIEW_H
#define OSGACTORAPPS_CAMERAVIEW_H 1

#include <osg/BoundingBox>
#include <osg/BoundingSphere>
#include <osg/Node>
#include <osg/Vec3d>

namespace osgActorApps {

/** A look-at camera in world space (model units). */
struct CameraView
{
    osg::Vec3d eye{0.0, -10.0, 0.0};
    osg::Vec3d center{0.0, 0.0, 0.0};
    osg::Vec3d up{0.0, 0.0, 1.0};
};

/** A view from the front-right and a little above (Z up, as in OSG), far enough back that the whole bounding
  * sphere fits a perspective camera of the given vertical field of view (degrees) and aspect ratio (width /
  * height). An invalid or empty bound gives the default view. */
CameraView frameBoundingSphere(const osg::BoundingSphere& bound, double fovyDegrees, double aspect);

/** The same view direction as frameBoundingSphere(), at the distance where all eight corners of the box (world
  * space) lie inside the perspective camera's frustum, looking at the box's centre: a wide, flat box (a stage seen
  * from the front) fills the picture, where its bounding sphere would leave it small. An invalid box gives the
  * default view. */
CameraView frameBox(const osg::BoundingBox& box, double fovyDegrees, double aspect);

/** The box (world space) that holds what the scene's actors (osgActor::ActorNode) draw as posed now, grown to hold
  * them anywhere along the stored paths their controllers follow (Controller::getFollowedPath(), such as a
  * TrajectoryPlayer's): each key's position, plus the actor's reach about its reference point at any heading.
  * Invalid when the scene has no actor drawing anything. */
osg::BoundingBox actorsBox(osg::Node& scene);

/** The sphere about the box that holds the scene's drawables as posed now, for framing. Tighter than the scene's
  * own bound, which holds each node's bound (an actor's, by default, holds every rotation of its joints); the
  * scene's bound where it has no drawable. */
osg::BoundingSphere shownBound(osg::Node& scene);

} // namespace osgActorApps

#endif
