/* Error handling across the API (docs/architecture.md): a rejected input says what and where, the previous state is
 * kept, nothing half-built is returned. */
#include "RobustnessUtil"
#include "nodes/NodeTestUtil"

#include <osgActor/MocapActor>

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <regex>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

/** The humanoid posed away from its defaults. */
osg::ref_ptr<ActorNode> readPosedHumanoid()
{
    osg::ref_ptr<ActorNode> actor = readHumanoid();
    for (unsigned d = 0; d < actor->getNumDofs(); ++d) actor->setDof(d, 0.1 * (d % 5));
    return actor;
}

bool isFinite(const osg::Matrixd& m)
{
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(m.ptr()[i])) return false;
    return true;
}

/** "file:LINE: what", with LINE a positive number. */
void expectFileAndLine(const std::string& error, const std::string& file)
{
    EXPECT_TRUE(std::regex_search(error, std::regex("^" + file + ":[1-9][0-9]*: .+"))) << error;
}

} // namespace

TEST(ErrorHandling, ABrokenReloadLeavesTheActorInTheSceneAsItWas)
{
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorNode> actor = readPosedHumanoid();
    scene->addChild(actor.get());
    runUpdate(*scene, 1);
    const ActorDefinitionPtr definition = actor->getDefinition();
    const std::vector<double> pose = actor->getDofs();
    const osg::Matrixd handMatrix = actor->getJointWorldMatrix(actor->getNumSkeletonNodes() - 1);

    // The file breaks half-way: the reader gives nothing, so a reload has nothing to put in the actor's place.
    std::string text = dataText("humanoid.actor");
    text = text.substr(0, text.size() / 2) + "\n joint }";
    std::istringstream in(text);
    const ActorReadResult reload = readActor(in, "humanoid.actor");
    ASSERT_FALSE(reload);
    EXPECT_EQ(reload.definition, nullptr);
    EXPECT_TRUE(reload.document.joints.empty());
    expectFileAndLine(reload.error, "humanoid\\.actor");

    runUpdate(*scene, 2);
    EXPECT_EQ(scene->getChild(0), actor.get());
    EXPECT_EQ(actor->getDefinition(), definition);
    EXPECT_EQ(actor->getDofs(), pose);
    EXPECT_EQ(actor->getJointWorldMatrix(actor->getNumSkeletonNodes() - 1), handMatrix);
}

TEST(ErrorHandling, RefusedDofWritesKeepEveryValue)
{
    osg::ref_ptr<ActorNode> actor = readPosedHumanoid();
    const std::vector<double> pose = actor->getDofs();

    EXPECT_FALSE(actor->setDof(0u, kNaN));
    EXPECT_FALSE(actor->setDof(1u, std::numeric_limits<double>::infinity()));
    EXPECT_FALSE(actor->setDof(actor->getNumDofs(), 0.5)) << "an index past the DOF vector";
    EXPECT_FALSE(actor->setDof("no_such_joint.rx", 0.5));
    EXPECT_FALSE(actor->setDof(actor->getDefinition()->getDofName(0) + "x", 0.5));

    std::vector<double> oneBad(pose.size(), 0.2);
    oneBad.back() = kNaN;
    EXPECT_FALSE(actor->setDofs(oneBad)) << "all or nothing: the last value spoils the write";
    EXPECT_FALSE(actor->setDofs(std::vector<double>(pose.size() + 1, 0.2))) << "one value too many";
    EXPECT_FALSE(actor->setDofs(std::vector<double>())) << "no values";
    EXPECT_EQ(actor->getDofs(), pose);
}

TEST(ErrorHandling, RefusedTransformsKeepTheOldOnes)
{
    osg::ref_ptr<ActorNode> actor = readPosedHumanoid();
    actor->setPreTranslation(osg::Vec3d(1, 2, 3));
    const osg::Matrixd before = actor->getActorMatrix();
    actor->setPreTranslation(osg::Vec3d(kNaN, 0, 0));
    actor->setPostTranslation(osg::Vec3d(0, std::numeric_limits<double>::infinity(), 0));
    actor->setPreRotation(osg::Quat(kNaN, 0, 0, 1));
    actor->setPostRotation(osg::Quat(0, 0, std::numeric_limits<double>::infinity(), 1));
    actor->setPostRotation(osg::Quat(1e300, 1e300, 0, 1)) /* finite parts, infinite length */;
    EXPECT_EQ(actor->getActorMatrix(), before);
}

TEST(ErrorHandling, HugeFiniteValuesNeverMakeAMatrixNonFinite)
{
    // Finite values at the end of the double range are taken (clamped), but a rotation mixing two of them (a
    // translation
    // DOF without limits, a pre- and a post-translation) must not overflow a matrix to infinity or NaN.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorNode> actor = readHumanoid();
    scene->addChild(actor);
    const double huge = std::numeric_limits<double>::max();
    for (unsigned d = 0; d < actor->getNumDofs(); ++d) actor->setDof(d, d % 4 == 3 ? -huge : huge);
    actor->setPreTranslation(osg::Vec3d(huge, huge, -huge));
    actor->setPreRotation(osg::Quat(0.7, osg::Vec3d(1, 1, 0)));
    actor->setPostTranslation(osg::Vec3d(huge, -huge, huge));
    actor->setPostRotation(osg::Quat(-1.1, osg::Vec3d(0, 1, 1)));
    runUpdate(*scene, 1);

    EXPECT_TRUE(isFinite(actor->getMatrix()));
    for (unsigned j = 0; j < actor->getNumSkeletonNodes(); ++j)
    {
        EXPECT_TRUE(isFinite(actor->getSkeletonNode(j)->getMatrix())) << actor->getDefinition()->getJointName(j);
        EXPECT_TRUE(isFinite(actor->getJointModelMatrix(j))) << actor->getDefinition()->getJointName(j);
        EXPECT_TRUE(isFinite(actor->getJointWorldMatrix(j))) << actor->getDefinition()->getJointName(j);
    }
}

TEST(ErrorHandling, ABrokenMocapFileGivesNoActorAndSaysWhere)
{
    const std::string path = std::string(OSGACTOR_TEST_BINARY_DIR) + "/broken.bvh";
    {
        std::ofstream out(path);
        out << "HIERARCHY\nROOT hips\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Xrotation Yrotation Zrotation\n"
               "  End Site\n  {\n    OFFSET 0 1 0\n  }\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n0 0 0\n0 nan 0\n";
    }
    std::string error;
    osg::ref_ptr<ActorNode> actor = readMocapActor(path, MocapActorOptions(), error);
    EXPECT_FALSE(actor);
    expectFileAndLine(error, ".*broken\\.bvh");
    EXPECT_NE(error.find(":15:"), std::string::npos) << "the line of the NaN: " << error;
}
