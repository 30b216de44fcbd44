// The children's union of the transforms an actor moves every frame (its translating root joint, the actor itself),
// taken in one visit of the children (osgActor/detail/ChildrenBound.h): whatever a user does to the children, the
// union osg::Group::computeBound() computes, bit for bit, and the bounds the nodes computed with OSG's union.
#include "NodeTestUtil"

#include <osgActor/ActorNode>
#include <osgActor/SkeletonNode>
#include <osgActor/detail/AffineBound.h>
#include <osgActor/detail/ChildrenBound.h>
#include <osgActor/detail/SkeletonNodeAccess.h>

#include <osg/Geometry>
#include <osg/MatrixTransform>
#include <osg/io_utils>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace osgActor;
using namespace osgActor::test;

namespace {

::testing::AssertionResult sameBits(const osg::BoundingSphere& actual, const osg::BoundingSphere& expected)
{
    static_assert(sizeof(osg::BoundingSphere) == 4 * sizeof(float), "a sphere is its centre and radius");
    if (std::memcmp(&actual, &expected, sizeof(osg::BoundingSphere)) == 0) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "centre " << actual.center() << " radius " << actual.radius()
                                         << ", expected centre " << expected.center() << " radius "
                                         << expected.radius();
}

/** A group whose children list can be handed to childrenBound(), as a subclass hands its own. */
class ListedGroup : public osg::Group
{
public:
    const osg::NodeList& children() const { return _children; }
};

/** The vertices of the box below geode (makeBox()). */
osg::Vec3Array& boxVertices(osg::Geode& geode)
{
    osg::Geometry* geometry = geode.getDrawable(0)->asGeometry();
    return *static_cast<osg::Vec3Array*>(geometry->getVertexArray());
}

/** A bound a callback computes instead of the node's computeBound(). */
struct FixedBound : osg::Node::ComputeBoundingSphereCallback
{
    explicit FixedBound(const osg::BoundingSphere& sphere) : sphere(sphere) {}
    osg::BoundingSphere computeBound(const osg::Node&) const override { return sphere; }
    osg::BoundingSphere sphere;
};

/** A skeleton node of a class of its own, whose bound OSG's MatrixTransform computes (SkeletonNode::computeBound()
  * takes the library's path for its own classes only) and whose subtree's shape is noted after. */
class OwnClassJoint : public SkeletonNode
{
};

} // namespace

TEST(ChildrenBound, IsOsgGroupsUnionAfterEveryEditOfTheChildren)
{
    osg::ref_ptr<ListedGroup> group = new ListedGroup;
    osg::ref_ptr<osg::MatrixTransform> turning = new osg::MatrixTransform(osg::Matrixd::translate(1.0, 0.0, 0.0));
    turning->addChild(makeBox(osg::Vec3(0.5f, 0.0f, 0.0f), 0.2f).get());
    osg::ref_ptr<osg::Geode> box = makeBox(osg::Vec3(-0.3f, 0.4f, 0.1f), 0.3f);
    group->addChild(turning.get());
    group->addChild(box.get());
    std::vector<const osg::Transform*> noted;
    const auto check = [&](const std::string& step) {
        noted.clear();
        const osg::BoundingSphere union_ =
            detail::childrenBound(group->children(), [&](const osg::Transform& t) { noted.push_back(&t); });
        EXPECT_TRUE(sameBits(union_, group->osg::Group::computeBound())) << step;
        EXPECT_TRUE(sameBits(detail::childrenBound(group->children()), group->osg::Group::computeBound())) << step;
        std::vector<const osg::Transform*> transforms;
        for (unsigned i = 0; i < group->getNumChildren(); ++i)
            if (const osg::Transform* t = group->getChild(i)->asTransform()) transforms.push_back(t);
        EXPECT_EQ(noted, transforms) << step << ": every child transform, in order";
    };
    check("two children");
    turning->setMatrix(osg::Matrixd::rotate(1.0, osg::Vec3d(0.0, 0.0, 1.0)) * osg::Matrixd::translate(1.0, 0.5, 0.0));
    check("a child transform moved");
    boxVertices(*box)[0] += osg::Vec3(2.0f, 0.0f, 0.0f);
    box->getDrawable(0)->dirtyBound();
    check("a child's geometry edited");
    turning->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    check("a child transform made absolute");
    turning->setReferenceFrame(osg::Transform::RELATIVE_RF);
    check("and relative again");
    box->setInitialBound(osg::BoundingSphere(osg::Vec3(0.0f, 0.0f, -4.0f), 0.5f));
    check("a child given an initial bound");
    box->setComputeBoundingSphereCallback(new FixedBound(osg::BoundingSphere(osg::Vec3(7.0f, 1.0f, 0.0f), 2.0f)));
    check("a child's bound computed by a callback");
    group->addChild(new osg::Geode);
    check("an empty child added (no bound)");
    group->addChild(makeBox(osg::Vec3(0.0f, -3.0f, 0.0f), 0.1f).get());
    check("a child added");
    group->removeChild(box.get());
    check("a child removed");
    group->setChild(0, makeBox(osg::Vec3(4.0f, 0.0f, 0.0f), 0.5f).get());
    check("a child replaced");
    group->insertChild(1, turning.get());
    check("a child inserted");
    // More children than the union holds the spheres of: the radius's step visits them again.
    for (int i = 0; i < 12; ++i)
    {
        group->addChild(makeBox(osg::Vec3(0.25f * float(i), -0.5f * float(i), 0.125f), 0.05f + 0.1f * float(i)).get());
        check("child " + std::to_string(i) + " of a dozen more added");
    }
    turning->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
    check("one of many made absolute");
    group->removeChildren(0, group->getNumChildren());
    check("no child left");
    group->addChild(new osg::Geode);
    check("only an empty child");
}

TEST(ChildrenBound, IsOsgGroupsUnionOfOneSphereBitForBit)
{
    // The actor's usual case: one child, its root joint. OSG's union of one sphere is not the sphere itself (the
    // box's centre and the radius about it are rounded), so the step is taken, not skipped.
    osg::ref_ptr<ListedGroup> group = new ListedGroup;
    osg::ref_ptr<osg::Geode> child = new osg::Geode;
    group->addChild(child.get());
    const float centres[] = {0.0f, 1e-7f, 0.3f, -2.7f, 1234.567f, -98765.43f, 3.4e37f};
    const float radii[] = {0.0f, 1e-8f, 0.1f, 3.3f, 777.7f, 1e30f};
    bool someDiffers = false;
    for (float x : centres)
        for (float r : radii)
        {
            const osg::BoundingSphere sphere(osg::Vec3(x, -0.7f * x, 0.1f + x), r);
            child->setComputeBoundingSphereCallback(new FixedBound(sphere));
            child->dirtyBound();
            EXPECT_TRUE(sameBits(detail::childrenBound(group->children()), group->osg::Group::computeBound()))
                << "centre " << sphere.center() << " radius " << r;
            someDiffers = someDiffers || !sameBits(group->osg::Group::computeBound(), sphere);
        }
    EXPECT_TRUE(someDiffers) << "the test can fail: OSG's union is not always its one sphere";
    // Spheres OSG's arithmetic does not expect: infinite, not a number, a negative zero radius.
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const osg::BoundingSphere odd[] = {osg::BoundingSphere(osg::Vec3(inf, 0.0f, 0.0f), 1.0f),
                                       osg::BoundingSphere(osg::Vec3(0.0f, nan, 0.0f), 1.0f),
                                       osg::BoundingSphere(osg::Vec3(1.0f, 2.0f, 3.0f), inf),
                                       osg::BoundingSphere(osg::Vec3(1.0f, 2.0f, 3.0f), nan),
                                       osg::BoundingSphere(osg::Vec3(1.0f, 2.0f, 3.0f), -0.0f)};
    for (const osg::BoundingSphere& sphere : odd)
    {
        child->setComputeBoundingSphereCallback(new FixedBound(sphere));
        child->dirtyBound();
        EXPECT_TRUE(sameBits(detail::childrenBound(group->children()), group->osg::Group::computeBound()))
            << "centre " << sphere.center() << " radius " << sphere.radius();
    }
}

TEST(ChildrenBound, IsOsgGroupsUnionOfRandomSpheres)
{
    // Groups of 1 to 12 children (more than the union holds, too), with spheres of every scale, some with no valid
    // radius, some of them transforms in an absolute frame (which do not count), against OSG's union.
    std::mt19937 random(28);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::uniform_int_distribution<int> numChildren(1, 12), scale(-20, 20), oneIn(0, 9);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    int valid = 0;
    for (int trial = 0; trial < 3000; ++trial)
    {
        osg::ref_ptr<ListedGroup> group = new ListedGroup;
        const int n = numChildren(random);
        for (int i = 0; i < n; ++i)
        {
            const float size = std::ldexp(1.0f, scale(random));
            float radius = size * (unit(random) + 1.0f);
            if (oneIn(random) == 0) radius = -1.0f;  // an empty child's
            if (oneIn(random) == 0) radius = -0.0f;  // valid, of no size
            if (trial % 97 == 0 && i == 0) radius = nan;
            osg::Vec3 centre(size * unit(random), size * unit(random), size * unit(random));
            if (trial % 89 == 0 && i == n - 1) centre.y() = nan;
            osg::ref_ptr<osg::Node> child = new osg::Group;
            if (oneIn(random) == 0)
            {
                osg::ref_ptr<osg::MatrixTransform> absolute = new osg::MatrixTransform;
                absolute->setReferenceFrame(osg::Transform::ABSOLUTE_RF);
                child = absolute;
            }
            child->setComputeBoundingSphereCallback(new FixedBound(osg::BoundingSphere(centre, radius)));
            group->addChild(child.get());
        }
        const osg::BoundingSphere osgs = group->osg::Group::computeBound();
        EXPECT_TRUE(sameBits(detail::childrenBound(group->children()), osgs)) << "trial " << trial << ", " << n
                                                                               << " children";
        valid += osgs.valid() ? 1 : 0;
    }
    EXPECT_GT(valid, 2000) << "the test can fail: most unions are spheres";
}

TEST(ChildrenBound, ATranslatingRootAndItsActorKeepTheirBoundsWhateverTheChildrenDo)
{
    // A root joint that slides (its bound follows the pose), carrying a box and a joint whose ball covers its turns.
    ActorDefinitionBuilder b("slider");
    b.addJoint("carriage").dofs(dofBit(Dof::TX) | dofBit(Dof::RZ));
    b.addJoint("arm", "carriage").offset(1, 0, 0).dofs(dofBit(Dof::RZ));
    b.addJoint("hand", "arm").offset(1, 0, 0);
    const BuildResult built = b.build();
    ASSERT_TRUE(built) << built.error;
    osg::ref_ptr<ActorNode> actor = new ActorNode(built.definition);
    actor->setPreTranslation(osg::Vec3d(3.0, -2.0, 0.5));
    SkeletonNode& carriage = *actor->getSkeletonNode(0u);
    SkeletonNode& arm = *actor->getSkeletonNode(1u);
    osg::ref_ptr<osg::Geode> box = makeBox(osg::Vec3(0.0f, 0.0f, 0.2f), 0.3f);
    carriage.addChild(box.get());
    actor->getSkeletonNode(2u)->addChild(makeBox(osg::Vec3(), 0.2f).get());
    ASSERT_FALSE(carriage.getBoundCoversRotations()); // the test can fail: the root takes the one-visit union's path
    ASSERT_TRUE(arm.getBoundCoversRotations());
    // The same children under a joint of a class of its own, whose bound OSG computes and whose subtree's shape is
    // noted after it: the shape the actor's cull reads must be the same.
    osg::ref_ptr<OwnClassJoint> twin = new OwnClassJoint;
    // Between frames, what a user may do to the root's children and the actor's, each through OSG's own calls.
    osg::ref_ptr<osg::Geode> besideRoot = makeBox(osg::Vec3(-1.0f, 4.0f, 0.0f), 0.6f);
    const std::vector<std::pair<std::string, std::function<void()>>> edits = {
        {"nothing", [] {}},
        {"the box's geometry edited",
         [&] {
             boxVertices(*box)[1] += osg::Vec3(0.0f, 3.0f, 0.0f);
             box->getDrawable(0)->dirtyBound();
         }},
        {"the arm's matrix set by hand", [&] { arm.setMatrix(osg::Matrixd::translate(0.5, 2.0, 0.0)); }},
        {"the arm scaled by hand", [&] { arm.setMatrix(osg::Matrixd::scale(2.0, 1.0, 1.0)); }},
        {"the arm made absolute", [&] { arm.setReferenceFrame(osg::Transform::ABSOLUTE_RF); }},
        {"the arm relative again", [&] { arm.setReferenceFrame(osg::Transform::RELATIVE_RF); }},
        {"a box added", [&] { carriage.addChild(makeBox(osg::Vec3(0.0f, -2.5f, 1.0f), 0.4f).get()); }},
        {"a box given an initial bound",
         [&] { box->setInitialBound(osg::BoundingSphere(osg::Vec3(0.0f, 0.0f, -4.0f), 0.5f)); }},
        {"the box's bound computed by a callback",
         [&] {
             box->setComputeBoundingSphereCallback(
                 new FixedBound(osg::BoundingSphere(osg::Vec3(0.0f, 6.0f, 0.0f), 1.5f)));
         }},
        {"the box removed", [&] { carriage.removeChild(box.get()); }},
        {"the box put back in the arm's place", [&] { carriage.setChild(0, box.get()); }},
        {"the arm put back", [&] { carriage.addChild(&arm); }},
        {"a box beside the root, under the actor", [&] { actor->addChild(besideRoot.get()); }},
        {"the root made absolute", [&] { carriage.setReferenceFrame(osg::Transform::ABSOLUTE_RF); }},
        {"the root relative again", [&] { carriage.setReferenceFrame(osg::Transform::RELATIVE_RF); }},
        {"the box beside the root removed", [&] { actor->removeChild(besideRoot.get()); }},
        {"nothing again", [] {}},
    };
    // Each edit, then a frame that moves the root (OSG's setReferenceFrame() dirties no bound: the root's move does).
    for (std::size_t frame = 0; frame < edits.size(); ++frame)
    {
        const std::string& edit = edits[frame].first;
        edits[frame].second();
        ASSERT_TRUE(actor->setDof("carriage.tx", 0.7 * double(frame)));
        ASSERT_TRUE(actor->setDof("carriage.rz", 0.4 * double(frame)));
        ASSERT_TRUE(actor->setDof("arm.rz", 1.1 * double(frame)));
        actor->update(nullptr);
        // The bounds as the library computed them before (OSG's union, moved by the matrix: AffineBound), bit for bit.
        EXPECT_TRUE(sameBits(carriage.getBound(),
                             detail::matrixTransformBound(carriage, carriage.osg::Group::computeBound())))
            << "after " << edit;
        EXPECT_TRUE(
            sameBits(actor->getBound(), detail::matrixTransformBound(*actor, actor->osg::Group::computeBound())))
            << "after " << edit;
        // The root's subtree's shape as a joint whose bound OSG computes notes it over the same children.
        twin->removeChildren(0, twin->getNumChildren());
        for (unsigned i = 0; i < carriage.getNumChildren(); ++i) twin->addChild(carriage.getChild(i));
        twin->setMatrix(carriage.getMatrix());
        const detail::SubtreeShape shape = detail::SkeletonNodeAccess::subtreeShape(carriage);
        const detail::SubtreeShape twinShape = detail::SkeletonNodeAccess::subtreeShape(*twin);
        EXPECT_EQ(shape.rigid, twinShape.rigid) << "after " << edit;
        EXPECT_EQ(shape.reach, twinShape.reach) << "after " << edit;
    }
}
