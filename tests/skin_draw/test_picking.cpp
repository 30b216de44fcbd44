// Picking: osgUtil::LineSegmentIntersector hits the deformed mesh (skinned on the CPU on demand at the actor's current
// pose) on both paths, not the bind pose the static vertex arrays hold.
#include "SkinDrawTestUtil"

#include <osgUtil/IntersectionVisitor>
#include <osgUtil/LineSegmentIntersector>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** The triangle of the mesh (three vertex indices) whose centroid moved farthest from the bind pose, among those
  * whose vertices all follow mostly the given joint of the skin. */
std::array<unsigned, 3> movedTriangleOf(const SkinnedMesh& mesh, unsigned skinJoint, const osg::Vec3Array& posed,
                                        const osg::Vec3Array& bind)
{
    const osg::PrimitiveSet& triangles = *mesh.getSurface()->getPrimitiveSet(0);
    std::array<unsigned, 3> best{};
    double farthest = -1.0;
    for (unsigned i = 0; i + 2 < triangles.getNumIndices(); i += 3)
    {
        const unsigned a = triangles.index(i), b = triangles.index(i + 1), c = triangles.index(i + 2);
        bool onJoint = true;
        for (unsigned v : {a, b, c}) onJoint = onJoint && mesh.getSkin()->getInfluenceJoints(v)[0] == skinJoint;
        if (!onJoint) continue;
        const osg::Vec3 moved = (posed[a] + posed[b] + posed[c] - bind[a] - bind[b] - bind[c]) / 3.0f;
        if (moved.length() > farthest) farthest = moved.length(), best = {a, b, c};
    }
    return best;
}

} // namespace

TEST(SkinnedMeshPicking, ALineThroughTheSwungForearmHitsItOnBothPaths)
{
    for (const SkinnedMesh::SkinningPath path : {SkinnedMesh::GPU_SKINNING, SkinnedMesh::CPU_SKINNING})
    {
        const RiggedModelActor read = readCesiumMan(path);
        FrameDriver driver(read.sceneNode.get());
        for (unsigned frame = 0; frame <= 20; ++frame) driver.frame(frame / 30.0);
        const SkinnedMesh& mesh = *read.skinnedMeshes[0];
        osg::ref_ptr<osg::Vec3Array> posed = new osg::Vec3Array;
        ASSERT_TRUE(mesh.computeSkinnedVertices(*read.actor, *posed));
        const osg::Vec3Array& bind = *static_cast<const osg::Vec3Array*>(
            const_cast<SkinnedMesh&>(mesh).getBindPoseGeometry(SkinningProfile::Compatibility)->getVertexArray());
        const std::vector<std::string>& names = mesh.getSkin()->getJointNames();
        const unsigned forearm = unsigned(std::find(names.begin(), names.end(), "Skeleton_arm_joint_L__3_") - names.begin());
        ASSERT_LT(forearm, names.size());
        const std::array<unsigned, 3> triangle = movedTriangleOf(mesh, forearm, *posed, bind);

        // Model space is world space here (the actor stands at the origin, no transform above it).
        const osg::Vec3d a = (*posed)[triangle[0]], b = (*posed)[triangle[1]], c = (*posed)[triangle[2]];
        const osg::Vec3d centroid = (a + b + c) / 3.0;
        osg::Vec3d normal = (b - a) ^ (c - a);
        normal.normalize();
        const osg::Vec3d bindCentroid =
            osg::Vec3d(bind[triangle[0]] + bind[triangle[1]] + bind[triangle[2]]) / 3.0;
        EXPECT_GT((centroid - bindCentroid).length(), 0.05) << "the forearm has not moved from the bind pose";

        // A line along the triangle's normal through its centroid, from outside the body.
        osg::ref_ptr<osgUtil::LineSegmentIntersector> line =
            new osgUtil::LineSegmentIntersector(centroid + normal * 0.3, centroid - normal * 0.02);
        osgUtil::IntersectionVisitor visitor(line.get());
        read.sceneNode->accept(visitor);
        ASSERT_TRUE(line->containsIntersections()) << (path == SkinnedMesh::GPU_SKINNING ? "GPU path" : "CPU path");
        const osgUtil::LineSegmentIntersector::Intersection& hit = line->getFirstIntersection();
        EXPECT_EQ(hit.drawable.get(), &mesh);
        EXPECT_LT((hit.getWorldIntersectPoint() - centroid).length(), 1e-4);
        EXPECT_EQ(hit.nodePath.front(), read.sceneNode.get());
    }
}
