// NameIndex: the flat index of joint names behind ActorDefinition::findJoint().
#include <osgActor/core/detail/NameIndex>

#include <gtest/gtest.h>

#include <string>
#include <vector>

using osgActor::NameIndex;

TEST(NameIndex, AnIndexNeverBuiltFindsNothing)
{
    const std::vector<std::string> names;
    EXPECT_EQ(NameIndex().find("hip", names), -1);
}

TEST(NameIndex, AnIndexOfNoNamesFindsNothing)
{
    const std::vector<std::string> names;
    NameIndex index;
    index.build(names);
    EXPECT_EQ(index.find("", names), -1);
    EXPECT_EQ(index.find("hip", names), -1);
}

TEST(NameIndex, NamesNotInTheListAreNotFoundEvenWhenTheyDifferByOneCharacterOrAreEmpty)
{
    const std::vector<std::string> names = {"hip", "knee", "ankle"};
    NameIndex index;
    index.build(names);
    EXPECT_EQ(index.find("hi", names), -1);
    EXPECT_EQ(index.find("hipp", names), -1);
    EXPECT_EQ(index.find("Hip", names), -1);
    EXPECT_EQ(index.find("", names), -1);
    EXPECT_EQ(index.find(std::string("knee\0", 5), names), -1);
}

TEST(NameIndex, EveryNameOfALargeListIsFoundAtItsPlace)
{
    // Enough names that many share a slot's first choice and the probing wraps past the table's end.
    std::vector<std::string> names;
    for (int i = 0; i < 5000; ++i) names.push_back("joint_" + std::to_string(i * 7919 % 5000));
    NameIndex index;
    index.build(names);
    for (std::size_t place = 0; place < names.size(); ++place)
        ASSERT_EQ(index.find(names[place], names), static_cast<int>(place)) << names[place];
    EXPECT_EQ(index.find("joint_5000", names), -1);
    EXPECT_EQ(index.find("joint_-1", names), -1);
}

TEST(NameIndex, NamesWithEmbeddedNulsAndLongNamesAreFoundWhole)
{
    const std::vector<std::string> names = {std::string("a\0b", 3), std::string("a"), std::string(300, 'x')};
    NameIndex index;
    index.build(names);
    EXPECT_EQ(index.find(std::string("a\0b", 3), names), 0);
    EXPECT_EQ(index.find("a", names), 1);
    EXPECT_EQ(index.find(std::string(300, 'x'), names), 2);
    EXPECT_EQ(index.find(std::string(299, 'x'), names), -1);
}

TEST(NameIndex, NamesGivenByAnAccessorAreFoundAndANameGivenTwiceIsFoundAtItsFirstPlace)
{
    struct Joint
    {
        std::string name;
        int depth;
    };
    // Enough names given twice that their second places probe past their first.
    std::vector<Joint> joints;
    for (int i = 0; i < 3000; ++i) joints.push_back(Joint{"j" + std::to_string(i % 1000), i});
    const auto nameOf = [&joints](std::size_t place) -> std::string_view { return joints[place].name; };
    NameIndex index;
    index.build(joints.size(), nameOf);
    for (int i = 0; i < 1000; ++i) ASSERT_EQ(index.find("j" + std::to_string(i), nameOf), i);
    EXPECT_EQ(index.find("j1000", nameOf), -1);
}
