#include "CameraView.h"

#include <osgActor/ActorNode>
#include <osgActor/core/Trajectory>

#include <osg/ComputeBoundsVisitor>
#include <osg/Math>
#include <osg/Transform>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace osgActorApps {

namespace {

/** From the centre towards the eye (unit, world space): looking along +Y (OSG's usual home direction), turned 30
  * degrees and raised 20, so that shapes read in depth. */
osg::Vec3d towardsEyeDirection()
{
    osg::Vec3d towardsEye(std::sin(osg::DegreesToRadians(30.0)), -std::cos(osg::DegreesToRadians(30.0)),
                          std::tan(osg::DegreesToRadians(20.0)));
    towardsEye.normalize();
    return towardsEye;
}

bool validField(double fovyDegrees, double aspect) { return fovyDegrees > 0.0 && fovyDegrees < 180.0 && aspect > 0.0; }

/** Grows world by the eight corners of box carried by matrix. */
void expandByCorners(osg::BoundingBox& world, const osg::BoundingBox& box, const osg::Matrixd& matrix)
{
    for (unsigned i = 0; i < 8; ++i) world.expandBy(osg::Vec3d(box.corner(i)) * matrix);
}

/** The actors below a node (not inside other actors), each with its parent's local-to-world matrix. */
class ActorPlacementFinder : public osg::NodeVisitor
{
public:
    ActorPlacementFinder() : osg::NodeVisitor(osg::NodeVisitor::TRAVERSE_ACTIVE_CHILDREN) {}

    void apply(osg::Transform& transform) override
    {
        osgActor::ActorNode* actor = dynamic_cast<osgActor::ActorNode*>(&transform);
        if (!actor)
        {
            traverse(transform);
            return;
        }
        osg::NodePath above = getNodePath();
        above.pop_back(); // the actor's own matrix is the actor's, not its parent's
        actors.emplace_back(actor, osg::computeLocalToWorld(above));
    }

    std::vector<std::pair<osgActor::ActorNode*, osg::Matrixd>> actors;
};

/** Grows world (world space) to hold the actor at every key of the paths its controllers follow: drawn is
  * what it draws now in its parent's frame, where its pre-transform (the reference point, moved by the players)
  * and the keys' positions are. */
void expandByPaths(osg::BoundingBox& world, const osgActor::ActorNode& actor, const osg::BoundingBox& drawn,
                   const osg::Matrixd& parentToWorld)
{
    // The reach about the reference point: horizontal (Z up) for any heading, and below and above it.
    const osg::Vec3d reference = actor.getPreTranslation();
    double reach = 0.0;
    for (unsigned i = 0; i < 8; ++i)
    {
        const osg::Vec3d offset = osg::Vec3d(drawn.corner(i)) - reference;
        reach = std::max(reach, std::hypot(offset.x(), offset.y()));
    }
    const double below = drawn.zMin() - reference.z();
    const double above = drawn.zMax() - reference.z();
    for (const osgActor::ControllerPtr& controller : actor.getControllers())
    {
        const osgActor::Trajectory* path = controller->getFollowedPath();
        if (!path) continue;
        for (const osgActor::TrajectoryKey& key : path->getKeys())
        {
            const osg::Vec3d at(key.position.x, key.position.y, key.position.z);
            const osg::BoundingBox there(at + osg::Vec3d(-reach, -reach, below), at + osg::Vec3d(reach, reach, above));
            expandByCorners(world, there, parentToWorld);
        }
    }
}

} // namespace

CameraView frameBoundingSphere(const osg::BoundingSphere& bound, double fovyDegrees, double aspect)
{
    CameraView view;
    if (!bound.valid() || bound.radius() <= 0.0f || !validField(fovyDegrees, aspect)) return view;

    // The sphere fits when it fits the narrower of the two fields of view.
    const double halfFovy = osg::DegreesToRadians(fovyDegrees) * 0.5;
    const double halfFovx = std::atan(std::tan(halfFovy) * aspect);
    const double distance = bound.radius() / std::sin(std::min(halfFovy, halfFovx));

    const osg::Vec3d towardsEye = towardsEyeDirection();
    view.center = osg::Vec3d(bound.center());
    view.eye = view.center + towardsEye * distance;
    view.up = osg::Vec3d(0.0, 0.0, 1.0);
    return view;
}

CameraView frameBox(const osg::BoundingBox& box, double fovyDegrees, double aspect)
{
    CameraView view;
    if (!box.valid() || !validField(fovyDegrees, aspect)) return view;

    // The camera's axes (world space): forward from the eye to the centre, right, and up in the picture.
    const osg::Vec3d forward = -towardsEyeDirection();
    osg::Vec3d right = forward ^ osg::Vec3d(0.0, 0.0, 1.0);
    right.normalize();
    const osg::Vec3d up = right ^ forward;
    // A corner at (x, y) across the picture and z along the line of sight from the centre stands at depth
    // distance + z from the eye: it is inside when |x| <= (distance + z) tan(half fov x), and the same for y. The
    // least distance that holds every corner; 5% of each half field kept free as a margin.
    const double tanHalfY = std::tan(osg::DegreesToRadians(fovyDegrees) * 0.5) * 0.95;
    const double tanHalfX = std::tan(osg::DegreesToRadians(fovyDegrees) * 0.5) * aspect * 0.95;
    const osg::Vec3d center(box.center());
    double distance = 0.0;
    for (unsigned i = 0; i < 8; ++i)
    {
        const osg::Vec3d offset = osg::Vec3d(box.corner(i)) - center;
        const double needed = std::max(std::fabs(offset * right) / tanHalfX, std::fabs(offset * up) / tanHalfY);
        distance = std::max(distance, needed - offset * forward);
    }
    if (!(distance > 0.0)) distance = 1.0; // a box with no extent (a point): a unit away rather than in it
    view.center = center;
    view.eye = center - forward * distance;
    view.up = osg::Vec3d(0.0, 0.0, 1.0);
    return view;
}

osg::BoundingBox actorsBox(osg::Node& scene)
{
    ActorPlacementFinder finder;
    scene.accept(finder);
    osg::BoundingBox world;
    for (const auto& placed : finder.actors)
    {
        // What the actor draws, in its parent's frame (the visitor applies the actor's own matrix).
        osg::ComputeBoundsVisitor drawn;
        placed.first->accept(drawn);
        const osg::BoundingBox& box = drawn.getBoundingBox();
        if (!box.valid()) continue;
        expandByCorners(world, box, placed.second);
        expandByPaths(world, *placed.first, box, placed.second);
    }
    return world;
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
