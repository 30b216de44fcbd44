#include "CameraView.h"

#include <osg/ComputeBoundsVisitor>
#include <osg/Math>

#include <algorithm>
#include <cmath>

namespace osgActorApps {

CameraView frameBoundingSphere(const osg::BoundingSphere& bound, double fovyDegrees, double aspect)
{
    CameraView view;
    if (!bound.valid() || bound.radius() <= 0.0f || fovyDegrees <= 0.0 || aspect <= 0.0) return view;

    // The sphere fits when it fits the narrower of the two fields of view.
    const double halfFovy = osg::DegreesToRadians(fovyDegrees) * 0.5;
    const double halfFovx = std::atan(std::tan(halfFovy) * aspect);
    const double distance = bound.radius() / std::sin(std::min(halfFovy, halfFovx));

    // Looking along +Y (OSG's usual home direction), turned 30 degrees and raised 20: shapes read in depth.
    osg::Vec3d towardsEye(std::sin(osg::DegreesToRadians(30.0)), -std::cos(osg::DegreesToRadians(30.0)),
                          std::tan(osg::DegreesToRadians(20.0)));
    towardsEye.normalize();
    view.center = osg::Vec3d(bound.center());
    view.eye = view.center + towardsEye * distance;
    view.up = osg::Vec3d(0.0, 0.0, 1.0);
    return view;
}

osg::BoundingSphere shownBound(osg::Node& scene)
{
    osg::ComputeBoundsVisitor drawn;
    scene.accept(drawn);
    const osg::BoundingBox& box = drawn.getBoundingBox();
    if (!box.valid()) return scene.getBound();
    return osg::BoundingSphere(box);
}

} // namespace osgActorApps
