#include <osgActor/core/ActorDefinitionBuilder>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace osgActor;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

::testing::AssertionResult refusedWith(const ActorDefinitionBuilder& builder, const std::string& fragment)
{
    const BuildResult result = builder.build();
    if (result) return ::testing::AssertionFailure() << "build() accepted the definition";
    if (result.error.find(fragment) == std::string::npos)
        return ::testing::AssertionFailure() << "error \"" << result.error << "\" does not mention \"" << fragment
                                             << "\"";
    return ::testing::AssertionSuccess();
}

} // namespace

// --- refusals first ---

TEST(Builder, RefusesAnEmptySkeleton)
{
    EXPECT_TRUE(refusedWith(ActorDefinitionBuilder("nobody"), "actor 'nobody': has no joints"));
}

TEST(Builder, RefusesAnEmptyJointName)
{
    ActorDefinitionBuilder b;
    b.addJoint("");
    EXPECT_TRUE(refusedWith(b, "empty name"));
}

TEST(Builder, RefusesADuplicateName)
{
    ActorDefinitionBuilder b;
    b.addJoint("hip");
    b.addJoint("knee", "hip");
    b.addJoint("knee", "hip");
    EXPECT_TRUE(refusedWith(b, "joint name 'knee' is used twice"));
}

TEST(Builder, RefusesAnUnknownParent)
{
    ActorDefinitionBuilder b;
    b.addJoint("hip");
    b.addJoint("knee", "thigh");
    EXPECT_TRUE(refusedWith(b, "joint 'knee' names an unknown parent 'thigh'"));
}

TEST(Builder, RefusesACycleAndNamesIt)
{
    ActorDefinitionBuilder b;
    b.addJoint("root");
    b.addJoint("a", "c");
    b.addJoint("b", "a");
    b.addJoint("c", "b");
    EXPECT_TRUE(refusedWith(b, "parent cycle"));
    const std::string error = b.build().error;
    EXPECT_NE(error.find("'a'"), std::string::npos) << error;
    EXPECT_NE(error.find("'b'"), std::string::npos) << error;
    EXPECT_NE(error.find("'c'"), std::string::npos) << error;
}

TEST(Builder, RefusesAJointThatIsItsOwnParent)
{
    ActorDefinitionBuilder b;
    b.addJoint("root");
    b.addJoint("loop", "loop");
    EXPECT_TRUE(refusedWith(b, "'loop' -> 'loop'"));
}

TEST(Builder, SaysWhichJointAnErrorIsAbout)
{
    EXPECT_EQ(ActorDefinitionBuilder("nobody").build().errorJoint, -1) << "no joint to blame";
    ActorDefinitionBuilder duplicate;
    duplicate.addJoint("hip");
    duplicate.addJoint("knee", "hip");
    duplicate.addJoint("knee", "hip");
    EXPECT_EQ(duplicate.build().errorJoint, 2) << "the second of the two";
    ActorDefinitionBuilder unknown;
    unknown.addJoint("knee", "thigh");
    unknown.addJoint("hip");
    EXPECT_EQ(unknown.build().errorJoint, 0);
    ActorDefinitionBuilder limits;
    limits.addJoint("hip");
    limits.addJoint("knee", "hip").dofs(dofBit(Dof::RX)).limits(Dof::RX, 1.0, -1.0);
    EXPECT_EQ(limits.build().errorJoint, 1);
    ActorDefinitionBuilder cycle;
    cycle.addJoint("root");
    cycle.addJoint("a", "b");
    cycle.addJoint("b", "a");
    const BuildResult result = cycle.build();
    EXPECT_TRUE(result.errorJoint == 1 || result.errorJoint == 2) << "a joint on the cycle: " << result.errorJoint;
    ActorDefinitionBuilder good;
    good.addJoint("root");
    EXPECT_EQ(good.build().errorJoint, -1);
}

TEST(Builder, RefusesBadLimits)
{
    ActorDefinitionBuilder reversed;
    reversed.addJoint("elbow").dofs(dofBit(Dof::RX)).limits(Dof::RX, 1.0, -1.0);
    EXPECT_TRUE(refusedWith(reversed, "'elbow.rx' has its minimum 1 above its maximum -1"));

    ActorDefinitionBuilder nan;
    nan.addJoint("elbow").dofs(dofBit(Dof::RX)).limits(Dof::RX, kNaN, 1.0);
    EXPECT_TRUE(refusedWith(nan, "'elbow.rx' has a NaN limit"));

    ActorDefinitionBuilder outside;
    outside.addJoint("elbow").dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.5, 1.0);
    EXPECT_TRUE(refusedWith(outside, "default value 0 outside its limits"));

    ActorDefinitionBuilder far;
    far.addJoint("root").dofs(dofBit(Dof::TX)).defaultValue(Dof::TX, 1e200);
    EXPECT_TRUE(refusedWith(far, "'root.tx' has its default value 1e+200 beyond +-1e+150"));
}

TEST(Builder, IgnoresLimitsOfInactiveDofs)
{
    ActorDefinitionBuilder b;
    b.addJoint("elbow").dofs(dofBit(Dof::RX)).limits(Dof::RY, 1.0, -1.0);
    EXPECT_TRUE(b.build());
}

TEST(Builder, RefusesNonFiniteOffsetsAndZeroRotations)
{
    ActorDefinitionBuilder offset;
    offset.addJoint("hip").offset(0.0, kInf, 0.0);
    EXPECT_TRUE(refusedWith(offset, "joint 'hip' has a non-finite offset"));

    ActorDefinitionBuilder far;
    far.addJoint("hip").offset(0.0, 0.0, -2e150);
    EXPECT_TRUE(refusedWith(far, "joint 'hip' has an offset beyond +-1e+150"));

    ActorDefinitionBuilder rotation;
    rotation.addJoint("hip").rotation(1.0, 0.0, 0.0, 0.0);
    EXPECT_TRUE(refusedWith(rotation, "joint 'hip' has a zero or non-finite offset rotation"));
}

TEST(Builder, RefusesBadWeights)
{
    ActorDefinitionBuilder b;
    b.addJoint("neck").dofs(dofBit(Dof::RY)).weight(Dof::RY, -0.5);
    EXPECT_TRUE(refusedWith(b, "'neck.ry' has weight -0.5"));
}

TEST(Builder, AFailedBuildLeavesTheBuilderUsable)
{
    ActorDefinitionBuilder b;
    b.addJoint("root");
    b.addJoint("arm", "shoulder");
    EXPECT_FALSE(b.build());
    b.addJoint("shoulder", "root");
    EXPECT_TRUE(b.build());
}

// --- what a valid build gives ---

TEST(Builder, SortsJointsParentFirstWhateverTheOrderGiven)
{
    ActorDefinitionBuilder b("arm");
    b.addJoint("hand", "forearm");
    b.addJoint("forearm", "upperarm");
    b.addJoint("upperarm", "shoulder");
    b.addJoint("shoulder");
    b.addJoint("thumb", "hand");
    const BuildResult result = b.build();
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    ASSERT_EQ(def.getNumJoints(), 5u);
    EXPECT_EQ(def.getName(), "arm");
    EXPECT_EQ(def.getJointName(0), "shoulder");
    EXPECT_EQ(def.getParent(0), kNoParent);
    for (unsigned j = 1; j < def.getNumJoints(); ++j)
    {
        ASSERT_GE(def.getParent(j), 0);
        EXPECT_LT(static_cast<unsigned>(def.getParent(j)), j) << def.getJointName(j);
    }
    EXPECT_EQ(def.getJointName(static_cast<unsigned>(def.getParent(static_cast<unsigned>(def.findJoint("thumb"))))),
              "hand");
}

TEST(Builder, LaysOutTheDofVectorJointByJointInRxToTzOrder)
{
    ActorDefinitionBuilder b;
    b.addJoint("root").dofs(Dof::TZ | Dof::RY).eulerOrder(EulerOrder::ZYX);
    b.addJoint("l_elbow", "root").dofs(dofBit(Dof::RX)).limits(Dof::RX, 0.0, 2.5).defaultValue(Dof::RX, 0.25);
    b.addJoint("fixed", "l_elbow");
    const BuildResult result = b.build();
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    ASSERT_EQ(def.getNumDofs(), 3u);
    EXPECT_EQ(def.getDofName(0), "root.ry");
    EXPECT_EQ(def.getDofName(1), "root.tz");
    EXPECT_EQ(def.getDofName(2), "l_elbow.rx");
    EXPECT_EQ(def.findDof("l_elbow.rx"), 2);
    EXPECT_EQ(def.findDof("l_elbow.ry"), -1);
    EXPECT_EQ(def.findDof("nobody.rx"), -1);
    EXPECT_EQ(def.findDof("l_elbow"), -1);
    EXPECT_EQ(def.getNumJointDofs(2), 0u);
    EXPECT_EQ(def.getDofDefault(2), 0.25);
    EXPECT_EQ(def.getDefaultDofs(), (std::vector<double>{0.0, 0.0, 0.25}));
    EXPECT_EQ(def.clampToLimits(2, 3.0), 2.5);
    EXPECT_EQ(def.clampToLimits(2, -1.0), 0.0);
    EXPECT_EQ(def.getEulerOrder(0), EulerOrder::ZYX);
}

TEST(Builder, FindsDofsOfJointsWhoseNamesContainDots)
{
    ActorDefinitionBuilder b;
    b.addJoint("mixamorig:Hips.001").dofs(kRotationDofs);
    const BuildResult result = b.build();
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.definition->findDof("mixamorig:Hips.001.rz"), 2);
}

TEST(Builder, ToBuilderRebuildsAnEqualDefinition)
{
    ActorDefinitionBuilder b("x");
    b.addJoint("root").dofs(kPaperDofs).limits(Dof::TX, -1.0, 1.0).weight(Dof::RZ, 0.5);
    b.addJoint("tip", "root").offset(1, 2, 3).rotation(0.5, 0, 0, 1).eulerOrder(EulerOrder::YZX)
        .translationMode(TranslationMode::BeforeRotation).dofs(Dof::RX | Dof::TY);
    const ActorDefinitionPtr original = b.build().definition;
    ASSERT_TRUE(original);
    const ActorDefinitionPtr copy = toBuilder(*original).build().definition;
    ASSERT_TRUE(copy);
    ASSERT_EQ(copy->getNumJoints(), original->getNumJoints());
    ASSERT_EQ(copy->getNumDofs(), original->getNumDofs());
    for (unsigned d = 0; d < original->getNumDofs(); ++d)
    {
        EXPECT_EQ(copy->getDofName(d), original->getDofName(d));
        EXPECT_EQ(copy->getDofMin(d), original->getDofMin(d));
        EXPECT_EQ(copy->getDofMax(d), original->getDofMax(d));
        EXPECT_EQ(copy->getDofWeight(d), original->getDofWeight(d));
    }
    EXPECT_EQ(copy->getEulerOrder(1), EulerOrder::YZX);
    EXPECT_EQ(copy->getTranslationMode(1), TranslationMode::BeforeRotation);
    EXPECT_EQ(copy->getOffsetTranslation(1), original->getOffsetTranslation(1));
}

TEST(Builder, BuildsFromSpecsHeldInsideLargerRecordsWithoutCopyingThem)
{
    // A document's joints: each spec is one member of a larger record, read in place one record size apart.
    struct Record
    {
        int line = 0;
        JointSpec spec;
        double padding[3] = {};
    };
    std::vector<Record> records(3);
    records[0].spec.name = "hand";
    records[0].spec.parent = "forearm";
    records[0].spec.translation = glm::dvec3(0.0, 0.0, -0.25);
    records[1].spec.name = "shoulder";
    records[1].spec.dofs[static_cast<unsigned>(Dof::RZ)].active = true;
    records[2].spec.name = "forearm";
    records[2].spec.parent = "shoulder";
    records[2].spec.dofs[static_cast<unsigned>(Dof::RX)] = DofSpec{true, -1.0, 2.0, 0.5, 3.0};
    const BuildResult result =
        ActorDefinitionBuilder::buildFrom("arm", JointSpecList(&records[0].spec, records.size(), sizeof(Record)));
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    EXPECT_EQ(def.getName(), "arm");
    ASSERT_EQ(def.getNumJoints(), 3u);
    EXPECT_EQ(def.getJointName(0), "shoulder");
    EXPECT_EQ(def.getJointName(1), "forearm");
    EXPECT_EQ(def.getJointName(2), "hand");
    EXPECT_EQ(def.getParent(2), 1);
    EXPECT_EQ(def.getOffsetTranslation(2), glm::dvec3(0.0, 0.0, -0.25));
    ASSERT_EQ(def.getNumDofs(), 2u);
    EXPECT_EQ(def.getDofIndex(1, Dof::RX), 1);
    EXPECT_EQ(def.getDofMin(1), -1.0);
    EXPECT_EQ(def.getDofMax(1), 2.0);
    EXPECT_EQ(def.getDofDefault(1), 0.5);
    EXPECT_EQ(def.getDofWeight(1), 3.0);

    // Errors name the record's index, as build() names the builder's.
    records[1].spec.parent = "nobody";
    const BuildResult refused =
        ActorDefinitionBuilder::buildFrom("arm", JointSpecList(&records[0].spec, records.size(), sizeof(Record)));
    EXPECT_FALSE(refused);
    EXPECT_EQ(refused.errorJoint, 1);
    EXPECT_NE(refused.error.find("'nobody'"), std::string::npos) << refused.error;
}
