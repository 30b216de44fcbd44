#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/Controller>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

#include <limits>

using namespace osgActor;

namespace {

ActorDefinitionPtr makeBody()
{
    ActorDefinitionBuilder b("body");
    b.addJoint("pelvis").dofs(Dof::RZ | Dof::TX);
    b.addJoint("l_hip", "pelvis").dofs(dofBit(Dof::RX));
    b.addJoint("l_knee", "l_hip").dofs(dofBit(Dof::RX));
    b.addJoint("neck", "pelvis").dofs(dofBit(Dof::RY)).limits(Dof::RY, -1.0, 1.0);
    return b.build().definition;
}

/** Writes one fixed value to every DOF it drives. */
class ConstantController : public Controller
{
public:
    explicit ConstantController(double value) : _value(value) {}
    void update(const ControllerContext& context, ControllerTarget& target) override
    {
        lastTime = context.time;
        for (unsigned d = 0; d < target.pose.getNumDofs(); ++d) writeDof(target.pose, d, _value);
    }
    std::shared_ptr<Controller> cloneController() const override
    {
        return std::make_shared<ConstantController>(*this);
    }
    double lastTime = -1.0;

private:
    double _value;
};

} // namespace

TEST(DofSelection, RefusesUnknownJoints)
{
    std::string error;
    const DofSelection selection = DofSelection::joints(*makeBody(), {"l_hip", "tail"}, false, &error);
    EXPECT_NE(error.find("no joint named 'tail'"), std::string::npos) << error;
    EXPECT_TRUE(selection.drivesAll()) << "a refused selection is the empty one";
}

TEST(DofSelection, SelectsJointsAndOptionallyTheirDescendants)
{
    const ActorDefinitionPtr body = makeBody();
    const DofSelection leg = DofSelection::joints(*body, {"l_hip"}, true);
    // DOF vector: pelvis.rz, pelvis.tx, l_hip.rx, l_knee.rx, neck.ry
    EXPECT_EQ(leg.weights(), (std::vector<float>{0, 0, 1, 1, 0}));
    const DofSelection hipOnly = DofSelection::joints(*body, {"l_hip"}, false);
    EXPECT_EQ(hipOnly.weights(), (std::vector<float>{0, 0, 1, 0, 0}));
    EXPECT_EQ(DofSelection().weight(3), 1.0);
}

TEST(Controller, BlendsByWeightAndSelection)
{
    ActorPose pose(makeBody());
    ActorTransforms transforms;
    ControllerTarget target{pose, transforms};

    auto legs = std::make_shared<ConstantController>(0.8);
    legs->setSelection(DofSelection::joints(*pose.getDefinition(), {"l_hip"}, true));
    auto half = std::make_shared<ConstantController>(0.4);
    half->setWeight(0.5);
    half->setSelection(DofSelection::joints(*pose.getDefinition(), {"l_knee", "neck"}, false));

    ControllerContext context;
    context.time = 2.5;
    EXPECT_TRUE(runControllers({legs, half}, context, target));
    EXPECT_EQ(legs->lastTime, 2.5);
    const std::vector<double> expected{0.0, 0.0, 0.8, 0.6, 0.2};
    for (unsigned d = 0; d < expected.size(); ++d) EXPECT_NEAR(pose.getDof(d), expected[d], 1e-15) << d;
}

TEST(Controller, DisabledOrZeroWeightControllersDoNotRun)
{
    ActorPose pose(makeBody());
    ActorTransforms transforms;
    ControllerTarget target{pose, transforms};
    auto off = std::make_shared<ConstantController>(1.0);
    off->setEnabled(false);
    auto zero = std::make_shared<ConstantController>(1.0);
    zero->setWeight(0.0);
    EXPECT_FALSE(runControllers({off, zero, nullptr}, ControllerContext(), target));
    EXPECT_EQ(pose.getDofs(), pose.getDefinition()->getDefaultDofs());
}

TEST(Controller, ControllersCannotBreakLimitsOrWriteNaN)
{
    ActorPose pose(makeBody());
    ActorTransforms transforms;
    ControllerTarget target{pose, transforms};
    auto big = std::make_shared<ConstantController>(5.0);
    runControllers({big}, ControllerContext(), target);
    EXPECT_EQ(pose.getDof(4), 1.0) << "neck.ry stays within its limits";
    auto nan = std::make_shared<ConstantController>(std::numeric_limits<double>::quiet_NaN());
    runControllers({nan}, ControllerContext(), target);
    EXPECT_EQ(pose.getDof(2), 5.0) << "NaN is refused, the old value kept";
}

TEST(Controller, WeightsAreClampedToUnitRange)
{
    ConstantController c(0.0);
    c.setWeight(3.0);
    EXPECT_EQ(c.getWeight(), 1.0);
    c.setWeight(-1.0);
    EXPECT_EQ(c.getWeight(), 0.0);
    c.setWeight(std::numeric_limits<double>::quiet_NaN());
    EXPECT_EQ(c.getWeight(), 0.0);
}

TEST(BlendAngle, TakesTheShorterWayRound)
{
    const double pi = glm::pi<double>();
    EXPECT_NEAR(blendAngle(0.0, 1.0, 0.5), 0.5, 1e-15);
    // From 170 to -170 degrees the short way passes through 180, not 0.
    const double a = 170.0 * pi / 180.0, b = -170.0 * pi / 180.0;
    EXPECT_NEAR(blendAngle(a, b, 0.5), pi, 1e-12);
    EXPECT_NEAR(blendAngle(a, b, 1.0), a + 20.0 * pi / 180.0, 1e-12);
}
