// Bounds: the drawable's bound (SkinBoundsJob, no per-vertex work in update) holds every skinned vertex on every frame
// of every test clip, and a camera that sees only a raised hand does not cull the actor.
#include "SkinDrawTestUtil"

#include <osgActor/core/Clip>

#include <osg/Polytope>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

osg::BoundingBox boxOf(const osg::Vec3Array& points)
{
    osg::BoundingBox box;
    for (const osg::Vec3& p : points) box.expandBy(p);
    return box;
}

double volume(const osg::BoundingBox& box)
{
    return double(box.xMax() - box.xMin()) * (box.yMax() - box.yMin()) * (box.zMax() - box.zMin());
}

/** Steps the actor through times, checking at each that the mesh's bound (and the drawable's own box, the union over
  * its one actor) holds every vertex; returns the volume ratios of the bound to the exact box. */
template <class SetPose>
std::vector<double> checkBoundsOver(osg::Node* root, ActorNode& actor, SkinnedMesh& mesh, const std::vector<double>& times,
                                    SetPose setPose)
{
    FrameDriver driver(root);
    std::vector<double> ratios;
    for (double t : times)
    {
        setPose(t);
        driver.update(t);
        osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
        EXPECT_TRUE(mesh.computeSkinnedVertices(actor, *vertices));
        const osg::BoundingBox bound = mesh.getSkinnedBound(actor);
        EXPECT_TRUE(holdsEvery(bound, *vertices)) << mesh.getName() << " at t = " << t;
        EXPECT_TRUE(holdsEvery(mesh.getBoundingBox(), *vertices)) << mesh.getName() << " at t = " << t;
        ratios.push_back(volume(bound) / volume(boxOf(*vertices)));
    }
    return ratios;
}

std::vector<double> timesOver(double duration, double fps)
{
    std::vector<double> times;
    for (unsigned k = 0; k <= unsigned(duration * fps + 1e-9); ++k) times.push_back(k / fps);
    return times;
}

} // namespace

TEST(SkinnedMeshBounds, HoldEveryVertexOnEveryFrameOfEveryTestClip)
{
    const RiggedModelActor read = readCesiumMan();
    SkinnedMesh& mesh = *read.skinnedMeshes[0];
    const std::vector<double> ratios = checkBoundsOver(read.sceneNode.get(), *read.actor, mesh,
                                                       timesOver(read.rigged.clips[0]->getDuration(), 60.0),
                                                       [](double) {});
    EXPECT_EQ(ratios.size(), unsigned(read.rigged.clips[0]->getDuration() * 60.0 + 1e-9) + 1);

    for (const SkinningMethod method : {SkinningMethod::LinearBlend, SkinningMethod::DualQuaternion})
    {
        SyntheticActor chain = makeChainActor(40, method);
        checkBoundsOver(chain.actor.get(), *chain.actor, *chain.mesh, timesOver(3.0, 20.0),
                        [&chain](double t) { poseSynthetic(*chain.actor, t); });
        SyntheticActor random = makeRandomActor(16, 200, 8, 5u, method);
        checkBoundsOver(random.actor.get(), *random.actor, *random.mesh, timesOver(3.0, 20.0),
                        [&random](double t) { poseSynthetic(*random.actor, t); });
    }
}

TEST(SkinnedMeshBounds, CesiumMansBoxIsWithinOneAndAHalfTimesTheExactBoxOnNineteenFramesInTwenty)
{
    // Issue 26's measure: the drawable's box (getBoundingBox(), what culling and near/far use; not the sphere OSG
    // derives from it) over the exact box of the deformed mesh, at 30 frames per second over the clip.
    const RiggedModelActor read = readCesiumMan();
    SkinnedMesh& mesh = *read.skinnedMeshes[0];
    FrameDriver driver(read.sceneNode.get());
    std::vector<double> ratios;
    for (double t : timesOver(read.rigged.clips[0]->getDuration(), 30.0))
    {
        driver.update(t);
        osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
        ASSERT_TRUE(mesh.computeSkinnedVertices(*read.actor, *vertices));
        const osg::BoundingBox bound = mesh.getBoundingBox();
        ASSERT_TRUE(holdsEvery(bound, *vertices)) << "at t = " << t;
        ratios.push_back(volume(bound) / volume(boxOf(*vertices)));
    }
    ASSERT_GE(ratios.size(), 30u);
    std::vector<double> sorted(ratios);
    std::sort(sorted.begin(), sorted.end());
    const double within =
        double(std::count_if(ratios.begin(), ratios.end(), [](double r) { return r <= 1.5; })) / ratios.size();
    std::ostringstream distribution;
    distribution << "Cesium Man: drawable box volume over the exact box's on " << ratios.size()
                 << " frames (30 per second): smallest " << sorted.front() << ", median " << sorted[sorted.size() / 2]
                 << ", largest " << sorted.back() << ", " << 100.0 * within << "% within 1.5; "
                 << mesh.getSkin()->getBlendSets().size() << " pieces";
    std::cout << distribution.str() << "\n";
    RecordProperty("bound_volume_ratio", distribution.str());
    EXPECT_GE(sorted.front(), 1.0);
    EXPECT_GE(within, 0.95);
}

TEST(SkinnedMeshBounds, ACameraThatSeesOnlyARaisedHandDoesNotCullTheActor)
{
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        const RiggedModelActor read = readCesiumMan(path);
        ActorNode& actor = *read.actor;
        SkinnedMesh& mesh = *read.skinnedMeshes[0];
        actor.removeController(actor.getControllers()[0]); // posed by hand here
        osg::ref_ptr<osg::Vec3Array> rest = new osg::Vec3Array;
        ASSERT_TRUE(mesh.computeSkinnedVertices(actor, *rest));
        const osg::BoundingBox restBox = boxOf(*rest);

        // The left arm raised as high as a turn of the shoulder takes the hand (a search over its three angles).
        const unsigned shoulder = unsigned(actor.getJointIndex("Skeleton_arm_joint_L__4_"));
        const unsigned hand = unsigned(actor.getJointIndex("Skeleton_arm_joint_L__2_"));
        const int firstDof = actor.getDofIndex("Skeleton_arm_joint_L__4_.rx");
        double best[3] = {0, 0, 0}, bestHeight = -1e9;
        for (int i = -4; i < 4; ++i)
            for (int j = -4; j < 4; ++j)
                for (int k = -4; k < 4; ++k)
                {
                    const double angles[3] = {i * M_PI / 4, j * M_PI / 4, k * M_PI / 4};
                    for (int d = 0; d < 3; ++d) actor.setDof(unsigned(firstDof + d), angles[d]);
                    const double height = actor.getJointModelMatrix(hand).getTrans().z();
                    if (height > bestHeight) std::copy(angles, angles + 3, best), bestHeight = height;
                }
        for (int d = 0; d < 3; ++d) actor.setDof(unsigned(firstDof + d), best[d]);
        EXPECT_GT(actor.getJointModelMatrix(hand).getTrans().z(), actor.getJointModelMatrix(shoulder).getTrans().z());

        FrameDriver driver(read.sceneNode.get());
        driver.update(0.0);
        osg::ref_ptr<osg::Vec3Array> posed = new osg::Vec3Array;
        ASSERT_TRUE(mesh.computeSkinnedVertices(actor, *posed));
        // The hand: the vertices above everything the rest pose reaches.
        osg::BoundingBox handBox;
        for (const osg::Vec3& p : *posed)
            if (p.z() > restBox.zMax() + 0.05f) handBox.expandBy(p);
        ASSERT_TRUE(handBox.valid()) << "the raised hand reaches no higher than the head";

        // A camera level with the hand, looking at it from in front, whose frustum is fitted to the hand's box: its
        // sides through the box's outermost corners, its near and far planes at the box's nearest and farthest.
        const osg::Vec3d centre = handBox.center();
        const osg::Vec3d eye = centre + osg::Vec3d(0.0, -1.5, 0.0);
        osgUtil::SceneView& view = driver.sceneView();
        view.setViewMatrixAsLookAt(eye, centre, osg::Vec3d(0, 0, 1));
        double left = 1e9, right = -1e9, bottom = 1e9, top = -1e9, nearest = 1e9, farthest = 0.0;
        for (unsigned c = 0; c < 8; ++c)
        {
            const osg::Vec3d corner = osg::Vec3d(handBox.corner(c)) * view.getViewMatrix(); // eye space: -z ahead
            const double depth = -corner.z();
            left = std::min(left, corner.x() / depth), right = std::max(right, corner.x() / depth);
            bottom = std::min(bottom, corner.y() / depth), top = std::max(top, corner.y() / depth);
            nearest = std::min(nearest, depth), farthest = std::max(farthest, depth);
        }
        const double margin = 1.001; // the box's own faces a hair inside
        nearest /= margin;
        farthest *= margin;
        view.setProjectionMatrixAsFrustum(left * margin * nearest, right * margin * nearest, bottom * margin * nearest,
                                          top * margin * nearest, nearest, farthest);
        view.getCullVisitor()->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
        osg::Polytope frustum;
        frustum.setToUnitFrustum();
        frustum.transformProvidingInverse(view.getViewMatrix() * view.getProjectionMatrix());
        EXPECT_TRUE(frustum.contains(handBox));
        // A bound of the rest pose (what a bound computed once holds) is outside this view.
        EXPECT_FALSE(frustum.contains(restBox)) << "the view sees more than the hand";

        driver.cull();
        const std::vector<const osg::Drawable*> drawn = driver.culledDrawables();
        EXPECT_EQ(drawn.size(), 1u) << (path == SkinnedMesh::GPU_SKINNING ? "GPU path" : "CPU path");
        const SkinnedMesh::Statistics statistics = mesh.getStatistics(actor);
        EXPECT_EQ(statistics.cpuSkinnings + statistics.paletteUploads, 1u);
    }
}
