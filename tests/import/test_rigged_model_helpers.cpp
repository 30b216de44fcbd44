// What every reader of rigged models shares (osgActor/import/RiggedModel): a node matrix as T * R * S, unique names,
// influences cut to eight, animations moved to start at 0. Values worked out by hand.
#include <osgActor/import/RiggedModel>

#include <gtest/gtest.h>

#include <glm/ext/matrix_transform.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <limits>

using namespace osgActor;

TEST(DecomposeNodeMatrix, RefusesMatricesThatAreNotTransforms)
{
    RiggedNode node;
    bool shear = false;
    glm::dmat4 projective(1.0);
    projective[2][3] = -1.0;
    EXPECT_EQ(decomposeNodeMatrix(projective, node, shear), "is not affine (its last row is not 0 0 0 1)");
    EXPECT_EQ(decomposeNodeMatrix(glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 0.0, 1.0)), node, shear),
              "has a zero scale");
    glm::dmat4 nan(1.0);
    nan[3][1] = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(decomposeNodeMatrix(nan, node, shear), "holds a number that is not finite");
}

TEST(DecomposeNodeMatrix, GivesTranslationRotationAndScaleAMirrorOnX)
{
    // T(1, 2, 3) * R(90 degrees about Z) * S(-2, 3, 4): x goes to (0, -2, 0), y to (-3, 0, 0), z to (0, 0, 4).
    const glm::dquat turn = glm::angleAxis(glm::half_pi<double>(), glm::dvec3(0.0, 0.0, 1.0));
    const glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 3.0)) * glm::mat4_cast(turn) *
                         glm::scale(glm::dmat4(1.0), glm::dvec3(-2.0, 3.0, 4.0));
    RiggedNode node;
    bool shear = true;
    EXPECT_EQ(decomposeNodeMatrix(m, node, shear), "");
    EXPECT_FALSE(shear);
    EXPECT_EQ(node.translation, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_NEAR(node.scale.x, -2.0, 1e-12);
    EXPECT_NEAR(node.scale.y, 3.0, 1e-12);
    EXPECT_NEAR(node.scale.z, 4.0, 1e-12);
    EXPECT_NEAR(std::abs(glm::dot(node.rotation, turn)), 1.0, 1e-12);
    glm::dmat4 sheared = m;
    sheared[1] += 0.5 * sheared[0];
    EXPECT_EQ(decomposeNodeMatrix(sheared, node, shear), "");
    EXPECT_TRUE(shear);
}

TEST(MakeNodeNamesUnique, NamesTheUnnamedAndNumbersTheRepeated)
{
    RiggedModel model;
    for (const char* name : {"hip", "", "hip", "node1", "knee"}) model.nodes.push_back(RiggedNode{name});
    EXPECT_EQ(makeNodeNamesUnique(model), (std::vector<int>{2, 3}));
    const char* expected[] = {"hip", "node1", "hip#2", "node1#3", "knee"};
    for (int n = 0; n < 5; ++n) EXPECT_EQ(model.nodes[n].name, expected[n]);
}

TEST(MakeAnimationNamesUnique, NamesTheUnnamedAndNumbersTheRepeated)
{
    RiggedModel model;
    for (const char* name : {"Walk", "", "Walk"}) model.animations.push_back(RiggedAnimation{name, {}});
    makeAnimationNamesUnique(model);
    EXPECT_EQ(model.animations[0].name, "Walk");
    EXPECT_EQ(model.animations[1].name, "animation1");
    EXPECT_EQ(model.animations[2].name, "Walk#2");
}

TEST(SetInfluences, AddsRepeatedJointsAndKeepsTheEightLargest)
{
    // Vertex 0: joint 3 twice (0.25 + 0.5 = 0.75) and joint 1 (0.5): two influences. Vertex 1: ten joints weighing
    // 0.1 to 1.0: the eight largest (joints 9 down to 2).
    std::vector<std::vector<JointWeight>> weights(2);
    weights[0] = {{3, 0.25f}, {1, 0.5f}, {3, 0.5f}};
    for (std::uint16_t j = 0; j < 10; ++j) weights[1].push_back(JointWeight{j, 0.1f * float(j + 1)});
    RiggedPrimitive primitive;
    primitive.positions.resize(2);
    EXPECT_EQ(setInfluences(primitive, weights), 1u);
    ASSERT_EQ(primitive.influencesPerVertex, 8u);
    EXPECT_EQ(primitive.joints[0], 3u);
    EXPECT_FLOAT_EQ(primitive.weights[0], 0.75f);
    EXPECT_EQ(primitive.joints[1], 1u);
    EXPECT_FLOAT_EQ(primitive.weights[1], 0.5f);
    EXPECT_FLOAT_EQ(primitive.weights[2], 0.0f);
    for (unsigned i = 0; i < 8; ++i)
    {
        EXPECT_EQ(primitive.joints[8 + i], 9u - i);
        EXPECT_FLOAT_EQ(primitive.weights[8 + i], 0.1f * float(10 - i));
    }
}

TEST(StartAnimationAtZero, LeavesAnAnimationItCannotMoveAsItWas)
{
    // 1e17 s before 0 and 1 s apart: 1e17 + 1 is 1e17 in a double.
    RiggedAnimation far{"far", {}};
    far.channels.push_back(AnimationChannel{0, AnimationPath::Rotation, KeyInterpolation::Linear, {-1e17, -1e17 + 16.0, 0.0, 1.0}, {}, {}, {}});
    double moved = 0.0;
    EXPECT_FALSE(startAnimationAtZero(far, moved));
    EXPECT_EQ(far.channels[0].times, (std::vector<double>{-1e17, -1e17 + 16.0, 0.0, 1.0}));
}

TEST(StartAnimationAtZero, MovesKeysBeforeZeroAndLeavesTheOthers)
{
    RiggedAnimation late{"late", {}};
    late.channels.push_back(AnimationChannel{0, AnimationPath::Rotation, KeyInterpolation::Linear, {0.5, 1.0}, {}, {}, {}});
    double moved = -1.0;
    EXPECT_TRUE(startAnimationAtZero(late, moved));
    EXPECT_EQ(moved, 0.0);
    EXPECT_EQ(late.channels[0].times, (std::vector<double>{0.5, 1.0}));
    RiggedAnimation early{"early", {}};
    early.channels.push_back(AnimationChannel{0, AnimationPath::Rotation, KeyInterpolation::Linear, {-0.5, 1.0}, {}, {}, {}});
    early.channels.push_back(AnimationChannel{1, AnimationPath::Translation, KeyInterpolation::Linear, {0.25}, {}, {}, {}});
    EXPECT_TRUE(startAnimationAtZero(early, moved));
    EXPECT_EQ(moved, 0.5);
    EXPECT_EQ(early.channels[0].times, (std::vector<double>{0.0, 1.5}));
    EXPECT_EQ(early.channels[1].times, (std::vector<double>{0.75}));
}
