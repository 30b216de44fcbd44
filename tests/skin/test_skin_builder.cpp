#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/skin/SkinBinding>
#include <osgActor/core/skin/SkinBuilder>

#include <glm/ext/matrix_transform.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace osgActor;

namespace {

const float kNaN = std::numeric_limits<float>::quiet_NaN();
const float kInf = std::numeric_limits<float>::infinity();

/** Two joints and three vertices, each following joint 0 alone: a skin build() accepts. */
SkinBuilder makeValidBuilder()
{
    SkinBuilder builder("body");
    builder.addJoint("hip");
    builder.addJoint("knee", glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 0.5)));
    for (int v = 0; v < 3; ++v)
    {
        builder.addVertex(glm::vec3(0.1f * v, 0.0f, 0.0f));
        builder.addInfluence(v, 0, 1.0f);
    }
    return builder;
}

::testing::AssertionResult refusedWith(const SkinBuilder& builder, const std::string& fragment)
{
    const SkinBuildResult result = builder.build();
    if (result) return ::testing::AssertionFailure() << "build() accepted the skin";
    if (result.error.find(fragment) == std::string::npos)
        return ::testing::AssertionFailure() << "error \"" << result.error << "\" does not mention \"" << fragment
                                             << "\"";
    return ::testing::AssertionSuccess();
}

} // namespace

// --- refusals first ---

TEST(SkinBuilder, RefusesASkinWithoutJoints)
{
    SkinBuilder builder("body");
    builder.addVertex(glm::vec3(0.0f));
    EXPECT_TRUE(refusedWith(builder, "skin 'body': has no joints"));
}

TEST(SkinBuilder, RefusesASkinWithoutVertices)
{
    SkinBuilder builder("body");
    builder.addJoint("hip");
    EXPECT_TRUE(refusedWith(builder, "skin 'body': has no vertices"));
}

TEST(SkinBuilder, RefusesAnEmptyOrDuplicateJointNameNamingTheJoint)
{
    SkinBuilder empty = makeValidBuilder();
    empty.addJoint("");
    EXPECT_TRUE(refusedWith(empty, "joint 2 '': has an empty name"));
    EXPECT_EQ(empty.build().errorJoint, 2);

    SkinBuilder duplicate = makeValidBuilder();
    duplicate.addJoint("hip");
    EXPECT_TRUE(refusedWith(duplicate, "joint 2 'hip': the name is used twice (joints 0 and 2)"));
}

TEST(SkinBuilder, RefusesABadInverseBindMatrixNamingTheJoint)
{
    glm::dmat4 notFinite(1.0);
    notFinite[3][1] = std::numeric_limits<double>::quiet_NaN();
    SkinBuilder a = makeValidBuilder();
    a.addJoint("ankle", notFinite);
    EXPECT_TRUE(refusedWith(a, "joint 2 'ankle': inverse bind matrix is not finite"));

    glm::dmat4 projective(1.0);
    projective[2][3] = 0.5; // a non-zero bottom row entry
    SkinBuilder b = makeValidBuilder();
    b.addJoint("ankle", projective);
    EXPECT_TRUE(refusedWith(b, "joint 2 'ankle': inverse bind matrix is not affine"));

    SkinBuilder c = makeValidBuilder();
    c.addJoint("ankle", glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 0.0, 1.0)));
    EXPECT_TRUE(refusedWith(c, "joint 2 'ankle': inverse bind matrix is singular"));
}

TEST(SkinBuilder, RefusesNonRigidInverseBindMatricesForDualQuaternions)
{
    SkinBuilder shear = makeValidBuilder();
    shear.setMethod(SkinningMethod::DualQuaternion);
    glm::dmat4 sheared(1.0);
    sheared[1][0] = 0.3;
    shear.addJoint("ankle", sheared);
    EXPECT_TRUE(refusedWith(shear, "joint 2 'ankle': inverse bind matrix has shear or non-uniform scale"));

    SkinBuilder stretched = makeValidBuilder();
    stretched.setMethod(SkinningMethod::DualQuaternion);
    stretched.addJoint("ankle", glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 1.0)));
    EXPECT_TRUE(refusedWith(stretched, "joint 2 'ankle': inverse bind matrix has shear or non-uniform scale"));

    SkinBuilder mirrored = makeValidBuilder();
    mirrored.setMethod(SkinningMethod::DualQuaternion);
    mirrored.addJoint("ankle", glm::scale(glm::dmat4(1.0), glm::dvec3(-1.0, 1.0, 1.0)));
    EXPECT_TRUE(refusedWith(mirrored, "joint 2 'ankle': inverse bind matrix mirrors"));

    SkinBuilder twoScales = makeValidBuilder();
    twoScales.setMethod(SkinningMethod::DualQuaternion);
    twoScales.addJoint("ankle", glm::scale(glm::dmat4(1.0), glm::dvec3(2.0)));
    EXPECT_TRUE(refusedWith(twoScales, "joint 2 'ankle': inverse bind matrix scales by 2 where joint 0 scales by 1"));

    // Linear blend skinning takes all of them.
    SkinBuilder linear = makeValidBuilder();
    linear.addJoint("ankle", sheared);
    EXPECT_TRUE(linear.build());
}

TEST(SkinBuilder, RefusesAttributeArraysOfTheWrongLength)
{
    SkinBuilder normals = makeValidBuilder();
    const std::vector<glm::vec3> two(2, glm::vec3(0, 0, 1));
    normals.setNormals(two);
    EXPECT_TRUE(refusedWith(normals, "skin 'body': has 2 normals for 3 vertices"));

    SkinBuilder tangents = makeValidBuilder();
    const std::vector<glm::vec4> four(4, glm::vec4(1, 0, 0, 1));
    tangents.setTangents(four);
    EXPECT_TRUE(refusedWith(tangents, "skin 'body': has 4 tangents for 3 vertices"));
}

TEST(SkinBuilder, RefusesBadVertexAttributesNamingTheVertex)
{
    SkinBuilder position = makeValidBuilder();
    std::vector<glm::vec3> positions(3, glm::vec3(0.0f));
    positions[1].y = kInf;
    position.setPositions(positions);
    EXPECT_TRUE(refusedWith(position, "skin 'body': vertex 1: position is not finite"));
    EXPECT_EQ(position.build().errorVertex, 1);

    std::vector<glm::vec3> normals(3, glm::vec3(0, 0, 1));
    normals[2] = glm::vec3(0.0f);
    SkinBuilder zeroNormal = makeValidBuilder();
    zeroNormal.setNormals(normals);
    EXPECT_TRUE(refusedWith(zeroNormal, "vertex 2: normal is zero"));
    normals[2] = glm::vec3(kNaN, 0, 1);
    SkinBuilder nanNormal = makeValidBuilder();
    nanNormal.setNormals(normals);
    EXPECT_TRUE(refusedWith(nanNormal, "vertex 2: normal is not finite"));

    std::vector<glm::vec4> tangents(3, glm::vec4(1, 0, 0, 1));
    tangents[0].w = 0.5f;
    SkinBuilder handedness = makeValidBuilder();
    handedness.setTangents(tangents);
    EXPECT_TRUE(refusedWith(handedness, "vertex 0: tangent handedness (w) is 0.5, not +1 or -1"));
    tangents[0] = glm::vec4(0, 0, 0, 1);
    SkinBuilder zeroTangent = makeValidBuilder();
    zeroTangent.setTangents(tangents);
    EXPECT_TRUE(refusedWith(zeroTangent, "vertex 0: tangent is zero"));
}

TEST(SkinBuilder, RefusesAnInfluenceOnAVertexThatDoesNotExist)
{
    SkinBuilder builder = makeValidBuilder();
    builder.addInfluence(7, 1, 0.5f);
    EXPECT_TRUE(refusedWith(builder, "skin 'body': influence 3 (joint 1) names vertex 7, but the skin has 3 vertices"));
}

TEST(SkinBuilder, RefusesAJointIndexOutOfRangeNamingTheVertex)
{
    SkinBuilder builder = makeValidBuilder();
    builder.addInfluence(1, 5, 0.5f);
    EXPECT_TRUE(refusedWith(builder, "skin 'body': vertex 1: joint index 5 is out of range (the skin has 2 joints)"));
    EXPECT_EQ(builder.build().errorVertex, 1);
}

TEST(SkinBuilder, RefusesNaNInfiniteAndNegativeWeightsNamingTheVertex)
{
    SkinBuilder nan = makeValidBuilder();
    nan.addInfluence(2, 1, kNaN);
    EXPECT_TRUE(refusedWith(nan, "vertex 2: weight of joint 1 is not finite"));

    SkinBuilder infinite = makeValidBuilder();
    infinite.addInfluence(2, 1, kInf);
    EXPECT_TRUE(refusedWith(infinite, "vertex 2: weight of joint 1 is not finite"));

    SkinBuilder negative = makeValidBuilder();
    negative.addInfluence(0, 1, -0.25f);
    EXPECT_TRUE(refusedWith(negative, "vertex 0: weight -0.25 of joint 1 is negative"));
}

TEST(SkinBuilder, RefusesWeightsSummingToZeroNamingTheVertex)
{
    SkinBuilder builder("body");
    builder.addJoint("hip");
    builder.addVertex(glm::vec3(0.0f));
    builder.addVertex(glm::vec3(1.0f));
    builder.addInfluence(0, 0, 1.0f);
    builder.addInfluence(1, 0, 0.0f); // glTF's padding: a zero weight is no influence
    EXPECT_TRUE(refusedWith(builder, "skin 'body': vertex 1: its weights sum to zero (it follows no joint)"));
    EXPECT_EQ(builder.build().errorVertex, 1);
}

TEST(SkinBuilder, RefusesOneJointWithTwoWeightsOnAVertex)
{
    SkinBuilder builder = makeValidBuilder();
    builder.addInfluence(1, 0, 0.5f);
    EXPECT_TRUE(refusedWith(builder, "vertex 1: joint 0 is given two non-zero weights"));
}

TEST(SkinBuilder, LeavesItselfUnchangedWhenItRefuses)
{
    SkinBuilder builder = makeValidBuilder();
    builder.addInfluence(1, 5, 0.5f);
    EXPECT_FALSE(builder.build());
    EXPECT_EQ(builder.getNumJoints(), 2u);
    EXPECT_EQ(builder.getNumVertices(), 3u);
    EXPECT_FALSE(builder.build()); // the same refusal again: nothing was consumed
}

// --- what it mends and how it lays the skin out ---

TEST(SkinBuilder, RenormalisesWeightsAndSortsThemLargestFirst)
{
    SkinBuilder builder("body");
    builder.addJoint("a");
    builder.addJoint("b");
    builder.addJoint("c");
    builder.addVertex(glm::vec3(0.0f));
    builder.addInfluence(0, 0, 1.0f);
    builder.addInfluence(0, 2, 3.0f);
    builder.addInfluence(0, 1, 4.0f);
    const SkinBuildResult result = builder.build();
    ASSERT_TRUE(result) << result.error;
    const Skin& skin = *result.skin;
    ASSERT_EQ(skin.getNumInfluences(0), 3u);
    EXPECT_EQ(skin.getInfluenceJoints(0)[0], 1u);
    EXPECT_EQ(skin.getInfluenceJoints(0)[1], 2u);
    EXPECT_EQ(skin.getInfluenceJoints(0)[2], 0u);
    EXPECT_FLOAT_EQ(skin.getInfluenceWeights(0)[0], 0.5f);
    EXPECT_FLOAT_EQ(skin.getInfluenceWeights(0)[1], 0.375f);
    EXPECT_FLOAT_EQ(skin.getInfluenceWeights(0)[2], 0.125f);
}

TEST(SkinBuilder, KeepsTheEightLargestOfMoreInfluences)
{
    SkinBuilder builder("body");
    for (int j = 0; j < 10; ++j) builder.addJoint("j" + std::to_string(j));
    builder.addVertex(glm::vec3(0.0f));
    // Weights 1..10 on joints 0..9: joints 0 and 1 (weights 1 and 2) are dropped; the kept ones sum to 52.
    for (unsigned j = 0; j < 10; ++j) builder.addInfluence(0, j, static_cast<float>(j + 1));
    const SkinBuildResult result = builder.build();
    ASSERT_TRUE(result) << result.error;
    const Skin& skin = *result.skin;
    ASSERT_EQ(skin.getNumInfluences(0), kMaxSkinInfluences);
    float sum = 0.0f;
    for (unsigned k = 0; k < kMaxSkinInfluences; ++k)
    {
        EXPECT_EQ(skin.getInfluenceJoints(0)[k], 9u - k);
        EXPECT_FLOAT_EQ(skin.getInfluenceWeights(0)[k], (10.0f - k) / 52.0f);
        sum += skin.getInfluenceWeights(0)[k];
    }
    EXPECT_NEAR(sum, 1.0f, 1e-6f);
}

TEST(SkinBuilder, GroupsVerticesByInfluenceCountAndMapsThemBackToTheFileOrder)
{
    SkinBuilder builder("body");
    builder.addJoint("a");
    builder.addJoint("b");
    builder.addJoint("c");
    // File order: vertex 0 has 3 influences, 1 has 1, 2 has 2, 3 has 1.
    const unsigned counts[4] = {3, 1, 2, 1};
    for (unsigned v = 0; v < 4; ++v)
    {
        builder.addVertex(glm::vec3(static_cast<float>(v), 0.0f, 0.0f));
        for (unsigned k = 0; k < counts[v]; ++k) builder.addInfluence(v, k, 1.0f + k);
    }
    const SkinBuildResult result = builder.build();
    ASSERT_TRUE(result) << result.error;
    const SkinVertices vertices = result.skin->getVertices();
    EXPECT_EQ(vertices.counts[0], 2u);
    EXPECT_EQ(vertices.counts[1], 1u);
    EXPECT_EQ(vertices.counts[2], 1u);
    // Skin order: the one-influence vertices 1 and 3 (in file order), then 2, then 0.
    const std::uint32_t expectedFileIndex[4] = {1, 3, 2, 0};
    for (unsigned i = 0; i < 4; ++i)
    {
        EXPECT_EQ(vertices.outputIndices[i], expectedFileIndex[i]);
        EXPECT_EQ(vertices.positions[i].x, static_cast<float>(expectedFileIndex[i]));
    }
    EXPECT_EQ(vertices.joints.size(), 1u + 1u + 2u + 3u);
    // File-order accessors see through the grouping.
    for (unsigned v = 0; v < 4; ++v)
    {
        EXPECT_EQ(result.skin->getNumInfluences(v), counts[v]);
        EXPECT_EQ(result.skin->getBindPosition(v).x, static_cast<float>(v));
    }
}

TEST(SkinBuilder, CutsASubrangeAcrossInfluenceGroups)
{
    SkinBuilder builder("body");
    builder.addJoint("a");
    builder.addJoint("b");
    builder.addJoint("c");
    // Two vertices of each count 1, 2, 3, in file order.
    for (unsigned v = 0; v < 6; ++v)
    {
        builder.addVertex(glm::vec3(static_cast<float>(v), 0.0f, 0.0f));
        for (unsigned k = 0; k <= v / 2; ++k) builder.addInfluence(v, k, 1.0f);
    }
    const SkinBuildResult result = builder.build();
    ASSERT_TRUE(result) << result.error;
    // Vertices 1..4 of the skin's order: one with 1 influence, two with 2, one with 3.
    const SkinVertices piece = result.skin->getVertices().subrange(1, 4);
    EXPECT_EQ(piece.size(), 4u);
    EXPECT_EQ(piece.counts[0], 1u);
    EXPECT_EQ(piece.counts[1], 2u);
    EXPECT_EQ(piece.counts[2], 1u);
    EXPECT_EQ(piece.joints.size(), 1u + 4u + 3u);
    EXPECT_EQ(piece.joints.data(), result.skin->getVertices().joints.data() + 1);
    EXPECT_EQ(piece.outputIndices[0], 1u);
    EXPECT_EQ(piece.outputIndices[3], 4u);
}

TEST(SkinBuilder, ChoosesTheInverseTransposeForNormalsOnlyWhereABindMatrixStretches)
{
    SkinBuilder rigid = makeValidBuilder();
    rigid.addJoint("ankle", glm::rotate(glm::scale(glm::dmat4(1.0), glm::dvec3(0.01)), 1.0, glm::dvec3(0, 1, 0)));
    ASSERT_TRUE(rigid.build());
    EXPECT_EQ(rigid.build().skin->getNormalTransform(), NormalTransform::LinearPart);

    SkinBuilder stretched = makeValidBuilder();
    stretched.addJoint("ankle", glm::scale(glm::dmat4(1.0), glm::dvec3(1.0, 2.0, 1.0)));
    ASSERT_TRUE(stretched.build());
    EXPECT_EQ(stretched.build().skin->getNormalTransform(), NormalTransform::InverseTranspose);

    stretched.setNormalTransform(NormalTransform::LinearPart);
    EXPECT_EQ(stretched.build().skin->getNormalTransform(), NormalTransform::LinearPart);
}

TEST(SkinBuilder, KeepsTheBindScaleOfADualQuaternionSkin)
{
    SkinBuilder builder("body");
    builder.setMethod(SkinningMethod::DualQuaternion);
    builder.addJoint("hip", glm::scale(glm::dmat4(1.0), glm::dvec3(0.01)));
    builder.addJoint("knee", glm::rotate(glm::scale(glm::dmat4(1.0), glm::dvec3(0.01)), 0.5, glm::dvec3(1, 0, 0)));
    builder.addVertex(glm::vec3(0.0f));
    builder.addInfluence(0, 1, 1.0f);
    const SkinBuildResult result = builder.build();
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.skin->getMethod(), SkinningMethod::DualQuaternion);
    EXPECT_NEAR(result.skin->getBindScale(), 0.01, 1e-12);
}

// --- binding to a definition ---

TEST(SkinBinding, RefusesAJointTheDefinitionLacks)
{
    ActorDefinitionBuilder definition("leg");
    definition.addJoint("hip");
    const ActorDefinitionPtr leg = definition.build().definition;
    const SkinPtr skin = makeValidBuilder().build().skin;
    const SkinBinding binding = bindSkinToDefinition(*skin, *leg);
    EXPECT_FALSE(binding);
    EXPECT_EQ(binding.error, "skin 'body': joint 1 'knee' is not a joint of actor 'leg'");
    EXPECT_EQ(binding.errorJoint, 1);
}

TEST(SkinBinding, MapsEachSkinJointToTheDefinitionJointOfTheSameName)
{
    ActorDefinitionBuilder definition("leg");
    definition.addJoint("root");
    definition.addJoint("knee", "hip");
    definition.addJoint("hip", "root");
    const ActorDefinitionPtr leg = definition.build().definition;
    const SkinPtr skin = makeValidBuilder().build().skin;
    const SkinBinding binding = bindSkinToDefinition(*skin, *leg);
    ASSERT_TRUE(binding) << binding.error;
    ASSERT_EQ(binding.definitionJoints.size(), 2u);
    EXPECT_EQ(leg->getJointName(binding.definitionJoints[0]), "hip");
    EXPECT_EQ(leg->getJointName(binding.definitionJoints[1]), "knee");
}
