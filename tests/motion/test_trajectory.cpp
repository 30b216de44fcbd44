#include <TestMath>

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/Trajectory>
#include <osgActor/mocap/TrajectoryCsv>

#include <gtest/gtest.h>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kPi = glm::pi<double>();

TrajectoryBuildResult readText(const std::string& text)
{
    std::istringstream in(text);
    return readTrajectoryCsv(in, "path.csv");
}

void expectError(const std::string& text, const std::string& fileLine, const std::string& what)
{
    const TrajectoryBuildResult result = readText(text);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.error.rfind(fileLine, 0), 0u) << result.error;
    EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

std::string dataFile(const std::string& name) { return std::string(OSGACTOR_TEST_SOURCE_DIR) + "/motion/data/" + name; }

ActorTransforms play(TrajectoryPlayer& player, double deltaTime)
{
    static ActorDefinitionPtr definition = [] {
        ActorDefinitionBuilder b("dot");
        b.addJoint("body");
        return b.build().definition;
    }();
    ActorPose pose(definition);
    ActorTransforms transforms;
    ControllerTarget target{pose, transforms};
    ControllerContext context;
    context.deltaTime = deltaTime;
    player.update(context, target);
    EXPECT_TRUE(target.transformsChanged);
    return transforms;
}

} // namespace

TEST(TrajectoryCsv, RefusesBrokenFiles)
{
    EXPECT_NE(readTrajectoryCsvFile("/nonexistent/path.csv").error.find("cannot open"), std::string::npos);
    expectError("", "path.csv:0: ", "no point");
    expectError("time,x,y,z,heading\n0,0,0,0\n", "path.csv:2: ", "4 fields");
    expectError("0,0,0,0,0\n1,0,nan,0,0\n", "path.csv:2: ", "y 'nan' is not a finite number");
    expectError("0,0,0,0,0\r\n# comment\r\n0,1,0,0,0\r\n", "path.csv:3: ", "does not come after");
    expectError("when,x,y,z,heading\n0,0,0,0,0\n", "path.csv:1: ", "header must be time,x,y,z,heading");
    expectError("0,0,0,0,0\ntime,x,y,z,heading\n", "path.csv:2: ", "time 'time' is not a number");
}

TEST(TrajectoryBuilder, RefusesUnorderedOrNonFinitePoints)
{
    EXPECT_FALSE(TrajectoryBuilder::build("p", {}));
    TrajectoryKey a, b;
    b.time = -1.0;
    EXPECT_NE(TrajectoryBuilder::build("p", {a, b}).error.find("point 1 does not come after"), std::string::npos);
    b.time = 1.0;
    b.heading = std::numeric_limits<double>::infinity();
    EXPECT_NE(TrajectoryBuilder::build("p", {a, b}).error.find("point 1 is not finite"), std::string::npos);
}

TEST(TrajectoryCsv, ReadsPointsInDegrees)
{
    const TrajectoryBuildResult result = readTrajectoryCsvFile(dataFile("cockroach.csv"));
    ASSERT_TRUE(result) << result.error;
    const std::vector<TrajectoryKey>& keys = result.trajectory->getKeys();
    ASSERT_EQ(keys.size(), 3u);
    EXPECT_EQ(result.trajectory->getName(), "cockroach");
    EXPECT_TRUE(vectorsNear(keys[2].position, glm::dvec3(2, 2, 0)));
    EXPECT_DOUBLE_EQ(keys[2].heading, kPi / 2);
}

TEST(TrajectoryPlayer, DrivesThePreTransformAlongThePath)
{
    const TrajectoryPtr path = readTrajectoryCsvFile(dataFile("cockroach.csv")).trajectory;
    ASSERT_TRUE(path);
    TrajectoryPlayer player(path);
    player.setPlayMode(PlayMode::Once);
    ActorTransforms t = play(player, 0.0);
    EXPECT_TRUE(vectorsNear(t.preTranslation, glm::dvec3(0, 0, 0)));
    t = play(player, 0.5);
    EXPECT_TRUE(vectorsNear(t.preTranslation, glm::dvec3(1, 0, 0), 1e-12));
    t = play(player, 1.0);
    EXPECT_TRUE(vectorsNear(t.preTranslation, glm::dvec3(2, 1, 0), 1e-12));
    EXPECT_NEAR(glm::angle(t.preRotation), kPi / 4, 1e-12) << "halfway through the turn";
    t = play(player, 5.0);
    EXPECT_TRUE(vectorsNear(t.preTranslation, glm::dvec3(2, 2, 0), 1e-12)) << "Once stops at the end";

    player.setPlayMode(PlayMode::Loop);
    player.seek(2.5);
    t = play(player, 0.0);
    EXPECT_TRUE(vectorsNear(t.preTranslation, glm::dvec3(1, 0, 0), 1e-12)) << "Loop starts again";
}

TEST(TrajectoryPlayer, PathTimeAtFollowsThePlayMode)
{
    const TrajectoryPtr path = readTrajectoryCsvFile(dataFile("cockroach.csv")).trajectory; // keys at 0, 1, 2 s
    ASSERT_TRUE(path);
    TrajectoryPlayer player(path);
    EXPECT_EQ(player.getPlayMode(), PlayMode::Loop) << "loops unless told otherwise, as a clip player";
    EXPECT_DOUBLE_EQ(player.pathTimeAt(5.0), 1.0);
    EXPECT_DOUBLE_EQ(player.pathTimeAt(-0.5), 1.5) << "before the start: the end of the previous loop";
    player.setPlayMode(PlayMode::PingPong);
    EXPECT_DOUBLE_EQ(player.pathTimeAt(3.0), 1.0) << "on the way back";
    EXPECT_DOUBLE_EQ(player.pathTimeAt(4.5), 0.5) << "out again";
    player.setPlayMode(PlayMode::Once);
    EXPECT_DOUBLE_EQ(player.pathTimeAt(5.0), 2.0) << "Once: held at the last key";
    EXPECT_DOUBLE_EQ(player.pathTimeAt(-1.0), 0.0) << "and before the first";

    // What update() writes is the path sampled at pathTimeAt(play time).
    player.seek(3.5);
    const ActorTransforms t = play(player, 0.0);
    std::size_t cursor = 0;
    EXPECT_TRUE(vectorsNear(t.preTranslation, path->sample(player.pathTimeAt(3.5), cursor).position, 1e-12));
}
