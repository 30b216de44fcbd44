// The bound of a transform an actor moves every frame (its translating root joint, the actor itself) computed without
// osg::Transform::computeBound()'s generic steps (osgActor/detail/AffineBound.h): for an affine matrix and a finite
// sphere, the very sphere OSG computes, bit for bit; anything else is left to OSG.
#include "NodeTestUtil"

#include <osgActor/ActorNode>
#include <osgActor/SkeletonNode>
#include <osgActor/detail/AffineBound.h>

#include <osg/MatrixTransform>
#include <osg/io_utils>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace osgActor;
using namespace osgActor::test;

namespace {

::testing::AssertionResult sameSphere(const osg::BoundingSphere& actual, const osg::BoundingSphere& expected)
{
    // Equal values (a zero may differ in sign: OSG multiplies the matrix by the identity first).
    if (actual.center() == expected.center() && actual.radius() == expected.radius())
        return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "centre " << actual.center() << " radius " << actual.radius()
                                         << ", OSG's centre " << expected.center() << " radius " << expected.radius();
}

/** A transform over three boxes placed apart, so that the children's sphere is off the transform's origin. */
osg::ref_ptr<osg::MatrixTransform> makeTransformOverBoxes()
{
    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform;
    transform->addChild(makeBox(osg::Vec3(0.3f, -0.2f, 0.9f), 0.25f).get());
    transform->addChild(makeBox(osg::Vec3(-0.4f, 0.1f, 0.2f), 0.1f).get());
    transform->addChild(makeBox(osg::Vec3(0.05f, 0.5f, -0.7f), 0.4f).get());
    return transform;
}

} // namespace

TEST(AffineBound, LeavesAProjectiveMatrixAndAnInfiniteSphereToOsg)
{
    osg::BoundingSphere sphere(osg::Vec3(1.0f, 2.0f, 3.0f), 0.5f);
    osg::Matrixd projective;
    projective(0, 3) = 0.25;
    EXPECT_FALSE(detail::moveBoundByAffine(sphere, projective));
    EXPECT_EQ(sphere.center(), osg::Vec3(1.0f, 2.0f, 3.0f)) << "untouched";
    osg::BoundingSphere infinite(osg::Vec3(std::numeric_limits<float>::infinity(), 0.0f, 0.0f), 1.0f);
    EXPECT_FALSE(detail::moveBoundByAffine(infinite, osg::Matrixd::translate(1.0, 0.0, 0.0)));
    osg::BoundingSphere notANumber(osg::Vec3(0.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f), 1.0f);
    EXPECT_FALSE(detail::moveBoundByAffine(notANumber, osg::Matrixd::translate(1.0, 0.0, 0.0)));
    // Through the node: what OSG computes.
    osg::ref_ptr<osg::MatrixTransform> transform = makeTransformOverBoxes();
    transform->setMatrix(projective);
    EXPECT_TRUE(sameSphere(detail::matrixTransformBound(*transform, transform->osg::Group::computeBound()), transform->osg::MatrixTransform::computeBound()));
}

TEST(AffineBound, AnEmptyTransformHasNoBound)
{
    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform(osg::Matrixd::translate(1.0, 2.0, 3.0));
    EXPECT_FALSE(detail::matrixTransformBound(*transform, transform->osg::Group::computeBound()).valid());
    EXPECT_FALSE(transform->osg::MatrixTransform::computeBound().valid()) << "as OSG";
}

TEST(AffineBound, GivesOsgsSphereForRigidScaledAndShearedMatrices)
{
    osg::ref_ptr<osg::MatrixTransform> transform = makeTransformOverBoxes();
    std::mt19937 random(28);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < 300; ++i)
    {
        const osg::Vec3d axis(unit(random), unit(random), unit(random) + 1.5);
        osg::Matrixd matrix = osg::Matrixd::rotate(3.0 * unit(random), axis) *
                              osg::Matrixd::translate(100.0 * unit(random), 5.0 * unit(random), 0.01 * unit(random));
        if (i % 3 == 1) matrix = osg::Matrixd::scale(2.0 + unit(random), 0.5, 1.0) * matrix;
        if (i % 3 == 2) matrix(1, 0) += unit(random); // sheared: still affine
        transform->setMatrix(matrix);
        osg::BoundingSphere moved = transform->osg::Group::computeBound();
        ASSERT_TRUE(detail::moveBoundByAffine(moved, matrix));
        EXPECT_TRUE(sameSphere(moved, transform->osg::MatrixTransform::computeBound())) << "matrix " << i;
    }
}

TEST(AffineBound, SumsInOsgsOrder)
{
    // A sum whose double rounding depends on its order, and whose float rounding then does: centre (1, 0, 1) moved by
    // a matrix whose first column is (1, 0, 2^-24, 2^-53 + 2^-80). In OSG's order ((1 + 0) + 2^-24) + (2^-53 + 2^-80)
    // is just above 1 + 2^-24, so the float is 1 + 2^-23; summed in any other order the double is 1 + 2^-24, a tie
    // the float rounds to 1. Random matrices almost never tell the orders apart, as the float rounding hides them.
    osg::ref_ptr<osg::MatrixTransform> transform = new osg::MatrixTransform;
    transform->addChild(new osg::Geode);
    transform->getChild(0)->setInitialBound(osg::BoundingSphere(osg::Vec3(1.0f, 0.0f, 1.0f), 0.5f));
    osg::Matrixd matrix;
    matrix(2, 0) = std::ldexp(1.0, -24);
    matrix(3, 0) = std::ldexp(1.0, -53) + std::ldexp(1.0, -80);
    transform->setMatrix(matrix);
    const osg::BoundingSphere osgs = transform->osg::MatrixTransform::computeBound();
    ASSERT_EQ(osgs.center().x(), 1.0f + std::ldexp(1.0f, -23)) << "the test can fail: OSG's order rounds up";
    EXPECT_TRUE(sameSphere(detail::matrixTransformBound(*transform, transform->osg::Group::computeBound()), osgs));
}

TEST(AffineBound, ATranslatingRootAndItsActorGetOsgsSpheres)
{
    // A root joint that slides and turns (its bound follows the pose), carrying an arm whose ball covers its turns.
    ActorDefinitionBuilder b("slider");
    b.addJoint("carriage").dofs(dofBit(Dof::TX) | dofBit(Dof::TY) | dofBit(Dof::RZ) | dofBit(Dof::RX));
    b.addJoint("arm", "carriage").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("hand", "arm").offset(1, 0, 0);
    const BuildResult built = b.build();
    ASSERT_TRUE(built) << built.error;
    osg::ref_ptr<ActorNode> actor = new ActorNode(built.definition);
    actor->getSkeletonNode(0u)->addChild(makeBox(osg::Vec3(0.0f, 0.0f, 0.2f), 0.3f).get());
    actor->getSkeletonNode(2u)->addChild(makeBox(osg::Vec3(), 0.2f).get());
    actor->setPreTranslation(osg::Vec3d(3.0, -2.0, 0.5));
    SkeletonNode& carriage = *actor->getSkeletonNode(0u);
    ASSERT_FALSE(carriage.getBoundCoversRotations()); // the test can fail: the root takes the path measured here
    for (int frame = 0; frame < 6; ++frame)
    {
        ASSERT_TRUE(actor->setDof("carriage.tx", 0.7 * frame));
        ASSERT_TRUE(actor->setDof("carriage.ty", -0.3 * frame));
        ASSERT_TRUE(actor->setDof("carriage.rz", 0.4 * frame));
        ASSERT_TRUE(actor->setDof("carriage.rx", 0.1 * frame));
        ASSERT_TRUE(actor->setDof("arm.rz", 1.1 * frame));
        actor->update(nullptr);
        EXPECT_TRUE(sameSphere(carriage.getBound(), carriage.osg::MatrixTransform::computeBound())) << "frame " << frame;
        EXPECT_TRUE(sameSphere(actor->getBound(), actor->osg::MatrixTransform::computeBound())) << "frame " << frame;
    }
}
