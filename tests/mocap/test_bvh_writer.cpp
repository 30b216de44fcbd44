#include "MocapTestUtil"
#include "ReferenceMocap"

#include <TestMath>

#include <osgActor/core/ClipBuilder>
#include <osgActor/mocap/BvhReader>
#include <osgActor/mocap/BvhWriter>
#include <osgActor/mocap/PositionsCsv>

#include <gtest/gtest.h>

#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

BvhImportOptions fileFrame()
{
    BvhImportOptions options;
    options.convertToZUp = false;
    return options;
}

/** Writes a real file back out, reads it again, and compares with the reference reading of the original. */
void expectRoundTrip(const std::string& path)
{
    SCOPED_TRACE(path);
    const MocapImport original = readBvhFile(path, fileFrame());
    ASSERT_TRUE(original) << original.error;
    std::stringstream written;
    std::string error;
    ASSERT_TRUE(writeBvh(written, *original.definition, original.clip.get(), error)) << error;
    const MocapImport again = readBvh(written, "written.bvh", fileFrame());
    ASSERT_TRUE(again) << again.error;
    EXPECT_TRUE(again.warnings.empty());
    ASSERT_EQ(again.clip->getNumFrames(), original.clip->getNumFrames());
    ASSERT_EQ(again.definition->getNumJoints(), original.definition->getNumJoints());

    const reference::Bvh bvh = reference::readBvh(path);
    const double size = extent(reference::bvhPositions(bvh, 0));
    ActorPose pose(again.definition);
    for (unsigned frame : {0u, again.clip->getNumFrames() / 2, again.clip->getNumFrames() - 1})
    {
        const std::vector<glm::dvec3> expected = reference::bvhPositions(bvh, frame);
        const std::vector<glm::dvec3> actual = posedOrigins(pose, *again.clip, frame);
        for (std::size_t j = 0; j < expected.size(); ++j)
            EXPECT_TRUE(vectorsNear(actual[j], expected[j], 1e-6 * size)) << "frame " << frame << " joint " << j;
    }
}

} // namespace

TEST(BvhWriter, RefusesWhatBvhCannotSay)
{
    std::string error;
    std::ostringstream out;
    const MocapImport zUp = readBvhFile(repositoryMocap("bvh/12_03.bvh")); // turned to Z-up by a root offset rotation
    ASSERT_TRUE(zUp) << zUp.error;
    EXPECT_FALSE(writeBvh(out, *zUp.definition, zUp.clip.get(), error));
    EXPECT_NE(error.find("joint 'Hips' has an offset rotation"), std::string::npos) << error;

    const MocapImport fileAxes = readBvhFile(repositoryMocap("bvh/12_03.bvh"), fileFrame());
    ClipBuilder keyed("keyed");
    keyed.addKey(keyed.addChannel("Hips.rx"), 0.0, 1.0);
    EXPECT_FALSE(writeBvh(out, *fileAxes.definition, keyed.build().clip.get(), error));
    EXPECT_NE(error.find("keyed"), std::string::npos) << error;
}

TEST(BvhWriter, RoundTripsRealFiles)
{
    expectRoundTrip(repositoryMocap("bvh/tpose.bvh"));         // position channels on 144 joints, Z-up, decimetres
    expectRoundTrip(assimpBvh("Boxing_Toes.bvh"));         // ZXY
    expectRoundTrip(repositoryMocap("bvh/12_03.bvh"));         // ZYX, CMU
}

TEST(PositionsCsv, RefusesAnEmptyRange)
{
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/tpose.bvh"), fileFrame());
    ASSERT_TRUE(imported) << imported.error;
    std::ostringstream out;
    std::string error;
    EXPECT_FALSE(writePositionsCsv(out, imported.definition, *imported.clip, 1, 5, error));
    EXPECT_NE(error.find("empty"), std::string::npos) << error;
}

TEST(PositionsCsv, WritesOneRowPerJointPerFrame)
{
    // A two-joint arm turning about Z: the hand is 2 along X, turned by the frame's angle (0 then 90 degrees).
    std::istringstream in("HIERARCHY\nROOT arm,1\n{\n OFFSET 1 0 0\n CHANNELS 1 Zrotation\n JOINT hand\n {\n"
                          "  OFFSET 2 0 0\n  CHANNELS 0\n }\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n0\n90\n180\n");
    const MocapImport imported = readBvh(in, "arm.bvh", fileFrame());
    ASSERT_TRUE(imported) << imported.error;
    std::ostringstream out;
    std::string error;
    ASSERT_TRUE(writePositionsCsv(out, imported.definition, *imported.clip, 0, 2, error)) << error;
    // Numbers are written exactly: cos(90 degrees) in doubles is 6.1e-17, so the hand's x is 1 + 2 * 6.1e-17.
    EXPECT_EQ(out.str(), "frame,joint,x,y,z\n"
                         "0,\"arm,1\",1,0,0\n0,hand,3,0,0\n"
                         "1,\"arm,1\",1,0,0\n1,hand,1.0000000000000002,2,0\n");
}
