/* A small articulated figure built in code, with coloured shape geometry on its joints, for the image tests. */
#ifndef OSGACTOR_TESTS_RENDER_TESTFIGURE_H
#define OSGACTOR_TESTS_RENDER_TESTFIGURE_H 1

#include <osgActor/ActorNode>
#include <osgActor/core/ActorDefinitionBuilder>

#include <osg/Geode>
#include <osg/Image>
#include <osg/Material>
#include <osg/ShapeDrawable>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace osgActor {
namespace test {

/** Geometry of one body part, coloured through a material (the default lighting ignores vertex colours). */
inline osg::ref_ptr<osg::Geode> makePart(osg::Shape* shape, const osg::Vec4& colour)
{
    osg::ref_ptr<osg::Geode> geode = new osg::Geode;
    geode->addDrawable(new osg::ShapeDrawable(shape));
    osg::ref_ptr<osg::Material> material = new osg::Material;
    material->setDiffuse(osg::Material::FRONT_AND_BACK, colour);
    material->setAmbient(osg::Material::FRONT_AND_BACK, colour * 0.3f);
    geode->getOrCreateStateSet()->setAttributeAndModes(material.get());
    return geode;
}

/** A limb segment hanging down -Z from its joint: a capsule of the given length. */
inline osg::ref_ptr<osg::Geode> makeSegment(float length, float radius, const osg::Vec4& colour)
{
    return makePart(new osg::Capsule(osg::Vec3(0.0f, 0.0f, -0.5f * length), radius, length - 2.0f * radius), colour);
}

/** A ball on a joint, so that the joint's own position is always covered by the actor's pixels. */
inline osg::ref_ptr<osg::Geode> makeJointBall(float radius)
{
    return makePart(new osg::Sphere(osg::Vec3(), radius), osg::Vec4(0.95f, 0.8f, 0.2f, 1.0f));
}

/** A stick figure 1.7 units tall, standing on the origin, facing -Y (towards a camera on -Y), Z up:
  * pelvis (root, rz) 0.95 above the floor; chest; head; l/r_shoulder (rx, ry, rz) and l/r_elbow (rx); l/r_hip (rx,
  * ry) and l/r_knee (rx), with a yellow ball on each limb joint. Left is +X. A positive shoulder.rx raises the arm
  * backwards; negative, forwards; a
  * shoulder.ry of -+1.57 raises the left / right arm sideways. */
inline osg::ref_ptr<ActorNode> makeTestFigure()
{
    ActorDefinitionBuilder b("figure");
    b.addJoint("pelvis").offset(0, 0, 0.95).dofs(dofBit(Dof::RZ));
    b.addJoint("chest", "pelvis").offset(0, 0, 0.45);
    b.addJoint("head", "chest").offset(0, 0, 0.12);
    for (const char* side : {"l", "r"})
    {
        const double x = side[0] == 'l' ? 1.0 : -1.0;
        const std::string s(side);
        b.addJoint(s + "_shoulder", "chest").offset(0.22 * x, 0, 0).dofs(kRotationDofs);
        b.addJoint(s + "_elbow", s + "_shoulder").offset(0, 0, -0.3).dofs(dofBit(Dof::RX))
            .limits(Dof::RX, -2.6, 0.0);
        b.addJoint(s + "_hip", "pelvis").offset(0.1 * x, 0, 0).dofs(Dof::RX | Dof::RY);
        b.addJoint(s + "_knee", s + "_hip").offset(0, 0, -0.45).dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 2.6);
    }
    const BuildResult result = b.build();
    EXPECT_TRUE(result) << result.error;
    if (!result) return nullptr;

    osg::ref_ptr<ActorNode> actor = new ActorNode(result.definition);
    const osg::Vec4 skin(0.95f, 0.75f, 0.6f, 1.0f);
    const osg::Vec4 shirt(0.2f, 0.6f, 0.9f, 1.0f);
    const osg::Vec4 trousers(0.25f, 0.3f, 0.35f, 1.0f);
    const osg::Vec4 leftMark(0.9f, 0.3f, 0.2f, 1.0f); // the left limbs are red, so mirror errors show
    actor->getSkeletonNode("pelvis")->addChild(
        makePart(new osg::Box(osg::Vec3(0, 0, 0.2f), 0.32f, 0.16f, 0.5f), shirt));
    actor->getSkeletonNode("head")->addChild(makePart(new osg::Sphere(osg::Vec3(0, 0, 0.13f), 0.12f), skin));
    for (const char* side : {"l", "r"})
    {
        const std::string s(side);
        const bool left = side[0] == 'l';
        actor->getSkeletonNode(s + "_shoulder")->addChild(makeSegment(0.3f, 0.05f, left ? leftMark : shirt));
        actor->getSkeletonNode(s + "_elbow")->addChild(makeSegment(0.28f, 0.045f, skin));
        actor->getSkeletonNode(s + "_hip")->addChild(makeSegment(0.45f, 0.07f, left ? leftMark : trousers));
        actor->getSkeletonNode(s + "_knee")->addChild(makeSegment(0.5f, 0.06f, trousers));
        for (const char* joint : {"_shoulder", "_elbow", "_hip", "_knee"})
            actor->getSkeletonNode(s + joint)->addChild(makeJointBall(0.075f));
    }
    return actor;
}

/** Poses member a of a crowd of test figures apart from the others (radians): arms, a hip, a knee and the turn of
  * the pelvis grow with a. */
inline void poseCrowdMember(ActorNode& actor, unsigned a)
{
    actor.setDof("l_shoulder.ry", -0.25 * a);
    actor.setDof("r_shoulder.rx", -0.2 * a);
    actor.setDof("l_hip.rx", -0.1 * a);
    actor.setDof("r_knee.rx", 0.15 * a);
    actor.setDof("pelvis.rz", 0.2 * a - 0.6);
}

/** The pixels of an 8-bit RGB image whose blue is not the background's: what was drawn over it. */
/** count test figures in a row along X (1.1 apart, every other one 0.3 back), each posed by poseCrowdMember() and
  * updated, added to parent. */
inline std::vector<osg::ref_ptr<ActorNode>> addPosedRow(osg::Group& parent, unsigned count)
{
    std::vector<osg::ref_ptr<ActorNode>> actors;
    for (unsigned a = 0; a < count; ++a)
    {
        osg::ref_ptr<ActorNode> actor = makeTestFigure();
        actor->setPreTranslation(osg::Vec3d(1.1 * a, 0.3 * (a % 2), 0.0));
        poseCrowdMember(*actor, a);
        actor->update(nullptr);
        actors.push_back(actor);
        parent.addChild(actor.get());
    }
    return actors;
}

inline unsigned countDrawnPixels(const osg::Image& image, const osg::Vec4& background)
{
    const unsigned char blue = static_cast<unsigned char>(std::lround(background[2] * 255));
    unsigned drawn = 0;
    for (int y = 0; y < image.t(); ++y)
        for (int x = 0; x < image.s(); ++x) drawn += image.data(x, y)[2] != blue;
    return drawn;
}

/** A flat floor, size x size units, its top at z = 0. */
inline osg::ref_ptr<osg::Geode> makeFloor(float size)
{
    return makePart(new osg::Box(osg::Vec3(0, 0, -0.02f), size, size, 0.04f), osg::Vec4(0.75f, 0.8f, 0.6f, 1.0f));
}

} // namespace test
} // namespace osgActor

#endif
