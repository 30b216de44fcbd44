// LocalToModelJob, the second step of forward kinematics: invalid jobs first, then model matrices of chains and
// branches against products worked out by hand (column-vector notation), and which joints a run composes.
#include <osgActor/core/LocalToModelJob>

#include "TestMath"

#include <cstdint>
#include <vector>

using namespace osgActor;
using osgActor::test::fromRows;
using osgActor::test::matricesNear;

namespace {

/** Five joints:      0
  *                 /   \
  *                1     3
  *                |     |
  *                2     4
  * 0 at (1, 0, 0) turned 90 degrees about Z; 1 one along its parent's X; 2 one along X again, turned 90 degrees about
  * Z; 3 one along its parent's Y; 4 two along Z, its axes doubled in length. */
struct Tree
{
    std::vector<int> parents{-1, 0, 1, 0, 3};
    std::vector<glm::dmat4> local{fromRows(0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0),
                                  fromRows(1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0),
                                  fromRows(0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0),
                                  fromRows(1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 0),
                                  fromRows(2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 2)};
    std::vector<const double*> targets;
    std::vector<glm::dmat4> model = std::vector<glm::dmat4>(5, glm::dmat4(7.0));
    std::vector<std::uint8_t> stale = std::vector<std::uint8_t>(5, 1);

    Tree()
    {
        for (const glm::dmat4& m : local) targets.push_back(&m[0][0]);
    }
    LocalToModelJob job()
    {
        LocalToModelJob j;
        j.parents = parents;
        j.local = targets;
        j.modelStale = stale;
        j.model = model;
        return j;
    }
};

// The model matrices of Tree, by hand: 0 maps X to Y and sits at (1, 0, 0); 1 is one along 0's X, so at (1, 1, 0);
// 2 is one further along the same direction, (1, 2, 0), and turned a quarter more, so its X is -X; 3 is one along
// 0's Y, which is -X: (0, 0, 0), axes as 0's; 4 adds two along Z and doubles the axes.
const glm::dmat4 kModel0 = fromRows(0, -1, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0);
const glm::dmat4 kModel1 = fromRows(0, -1, 0, 1, 1, 0, 0, 1, 0, 0, 1, 0);
const glm::dmat4 kModel2 = fromRows(-1, 0, 0, 1, 0, -1, 0, 2, 0, 0, 1, 0);
const glm::dmat4 kModel3 = fromRows(0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0);
const glm::dmat4 kModel4 = fromRows(0, -2, 0, 0, 2, 0, 0, 0, 0, 0, 2, 2);

} // namespace

// --- invalid jobs are refused and touch nothing ---

TEST(LocalToModelJob, RefusesSpansOfTheWrongSize)
{
    Tree tree;
    const std::vector<const double*> fourTargets(tree.targets.begin(), tree.targets.begin() + 4);
    std::vector<glm::dmat4> sixModels(6);
    std::vector<std::uint8_t> fourFlags(4, 1);
    for (unsigned wrong = 0; wrong < 3; ++wrong)
    {
        LocalToModelJob job = tree.job();
        switch (wrong)
        {
        case 0: job.local = fourTargets; break;
        case 1: job.model = sixModels; break;
        case 2: job.modelStale = fourFlags; break;
        }
        EXPECT_FALSE(job.validate()) << "span " << wrong;
        EXPECT_FALSE(job.run()) << "span " << wrong;
    }
    EXPECT_EQ(tree.model[0], glm::dmat4(7.0)) << "a refused run touches nothing";
    EXPECT_EQ(tree.stale, std::vector<std::uint8_t>(5, 1));
}

TEST(LocalToModelJob, RefusesParentsThatDoNotComeFirst)
{
    Tree tree;
    for (int badParent : {2, 4, 7, -2})
    {
        tree.parents[2] = badParent; // itself, a later joint, none at all, below -1
        EXPECT_FALSE(tree.job().validate()) << badParent;
        EXPECT_FALSE(tree.job().run()) << badParent;
    }
    EXPECT_EQ(tree.model[2], glm::dmat4(7.0));
    tree.parents[2] = 0;
    EXPECT_TRUE(tree.job().validate()) << "any earlier joint";
}

TEST(LocalToModelJob, AcceptsAnEmptySkeleton)
{
    LocalToModelJob job;
    EXPECT_TRUE(job.validate());
    EXPECT_TRUE(job.run());
}

// --- what it composes ---

TEST(LocalToModelJob, ComposesChainsAndBranchesParentsFirst)
{
    Tree tree;
    ASSERT_TRUE(tree.job().run());
    EXPECT_TRUE(matricesNear(tree.model[0], kModel0, 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[1], kModel1, 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[2], kModel2, 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[3], kModel3, 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[4], kModel4, 1e-15));
    EXPECT_EQ(tree.stale, std::vector<std::uint8_t>(5, 0)) << "the flags are consumed";
}

TEST(LocalToModelJob, ComposesAStaleJointAndItsDescendantsOnly)
{
    Tree tree;
    ASSERT_TRUE(tree.job().run());
    // Joint 3 now sits two along its parent's Y, which is -X: at (-1, 0, 0), and 4 two above it. Joints 1 and 2 are
    // not composed again (their matrices are overwritten here so that a write would show).
    tree.local[3] = fromRows(1, 0, 0, 0, 0, 1, 0, 2, 0, 0, 1, 0);
    tree.model[1] = tree.model[2] = glm::dmat4(7.0);
    tree.stale = {0, 0, 0, 1, 0};
    ASSERT_TRUE(tree.job().run());
    EXPECT_EQ(tree.model[1], glm::dmat4(7.0));
    EXPECT_EQ(tree.model[2], glm::dmat4(7.0));
    EXPECT_TRUE(matricesNear(tree.model[3], fromRows(0, -1, 0, -1, 1, 0, 0, 0, 0, 0, 1, 0), 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[4], fromRows(0, -2, 0, -1, 2, 0, 0, 0, 0, 0, 2, 2), 1e-15));
    EXPECT_EQ(tree.stale, std::vector<std::uint8_t>(5, 0));
}

TEST(LocalToModelJob, WithoutFlagsComposesEveryJoint)
{
    Tree tree;
    LocalToModelJob job = tree.job();
    job.modelStale = {};
    ASSERT_TRUE(job.run());
    EXPECT_TRUE(matricesNear(tree.model[2], kModel2, 1e-15));
    EXPECT_TRUE(matricesNear(tree.model[4], kModel4, 1e-15));
}

TEST(MultiplyAffine, EqualsTheFullProduct)
{
    const glm::dmat4 a = fromRows(0.2, -0.9, 0.1, 4, 0.7, 0.3, -0.5, -2, 0.1, 0.4, 0.8, 1);
    const glm::dmat4 b = fromRows(1, 2, 3, 4, -1, 0.5, 2, 5, 0, 0.25, -3, 6);
    EXPECT_TRUE(matricesNear(multiplyAffine(a, b), a * b, 1e-14));
}
