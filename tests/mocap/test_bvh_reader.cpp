#include "MocapTestUtil"
#include "ReferenceMocap"

#include <TestMath>

#include <osgActor/mocap/BvhReader>

#include <gtest/gtest.h>

#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/ext/scalar_constants.hpp>

#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

MocapImport readText(const std::string& text, const BvhImportOptions& options = BvhImportOptions())
{
    std::istringstream in(text);
    return readBvh(in, "inline.bvh", options);
}

/** Expects an error that starts with file:line and mentions what. */
void expectError(const std::string& text, const std::string& fileLine, const std::string& what)
{
    const MocapImport result = readText(text);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.definition, nullptr) << "nothing half-built";
    EXPECT_EQ(result.clip, nullptr);
    EXPECT_EQ(result.error.rfind(fileLine, 0), 0u) << result.error;
    EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

const char* const kTwoJoints = "HIERARCHY\n"
                               "ROOT hips\n{\n  OFFSET 0 0 0\n"
                               "  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n"
                               "  JOINT knee\n  {\n    OFFSET 0 -1 0\n    CHANNELS 1 Xrotation\n"
                               "    End Site\n    {\n      OFFSET 0 -1 0\n    }\n  }\n}\n"
                               "MOTION\nFrames: 2\nFrame Time: 0.5\n";

BvhImportOptions fileFrame()
{
    BvhImportOptions options;
    options.convertToZUp = false;
    options.endSitesAsJoints = false;
    return options;
}

/** Our import of a real file against the reference computation, at several frames, to 1e-6 of its size. */
void expectMatchesReference(const std::string& path, bool absoluteRoot = false)
{
    SCOPED_TRACE(path);
    BvhImportOptions options = fileFrame();
    options.endSitesAsJoints = true;
    options.absoluteRootPosition = absoluteRoot;
    const MocapImport imported = readBvhFile(path, options);
    ASSERT_TRUE(imported) << imported.error;
    ASSERT_TRUE(imported.clip);
    const reference::Bvh bvh = reference::readBvh(path);
    ASSERT_EQ(imported.clip->getNumFrames(), bvh.frames.size());
    ASSERT_EQ(imported.definition->getNumJoints(), bvh.joints.size());
    EXPECT_NEAR(imported.clip->getFrameRate(), 1.0 / bvh.frameTime, 1e-9);

    ActorPose pose(imported.definition);
    const unsigned last = imported.clip->getNumFrames() - 1;
    const double size = extent(reference::bvhPositions(bvh, 0, absoluteRoot));
    ASSERT_GT(size, 0.0);
    for (unsigned frame : {0u, 1u, last / 3, last / 2, last})
    {
        if (frame > last) continue;
        SCOPED_TRACE("frame " + std::to_string(frame));
        const std::vector<glm::dvec3> expected = reference::bvhPositions(bvh, frame, absoluteRoot);
        const std::vector<glm::dvec3> actual = posedOrigins(pose, *imported.clip, frame);
        for (std::size_t j = 0; j < bvh.joints.size(); ++j)
        {
            const std::string name = bvh.joints[j].endSite ? bvh.joints[bvh.joints[j].parent].name + "_end"
                                                           : bvh.joints[j].name;
            const int ours = imported.definition->findJoint(name);
            ASSERT_GE(ours, 0) << name;
            EXPECT_TRUE(vectorsNear(actual[static_cast<unsigned>(ours)], expected[j], 1e-6 * size)) << name;
        }
    }
}

} // namespace

// --- invalid input first ---

TEST(BvhReader, RefusesAnEmptyFile) { expectError("", "inline.bvh:0: ", "HIERARCHY"); }

TEST(BvhReader, RefusesAMissingFile)
{
    const MocapImport result = readBvhFile("/nonexistent/walk.bvh");
    EXPECT_FALSE(result);
    EXPECT_NE(result.error.find("/nonexistent/walk.bvh: cannot open"), std::string::npos) << result.error;
}

TEST(BvhReader, RefusesAHierarchyCutShort)
{
    expectError("HIERARCHY\nROOT hips\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation", "inline.bvh:5: ", "CHANNELS");
    expectError("HIERARCHY\nROOT hips\n{\n  OFFSET 0 0 0\n", "inline.bvh:4: ", "missing '}'");
}

TEST(BvhReader, RefusesUnknownAndRepeatedChannels)
{
    expectError("HIERARCHY\nROOT hips\n{\n OFFSET 0 0 0\n CHANNELS 2 Zrotation Wrotation\n}\n", "inline.bvh:5: ",
                "unknown channel 'Wrotation'");
    expectError("HIERARCHY\nROOT hips\n{\n OFFSET 0 0 0\n CHANNELS 2 Zrotation Zrotation\n}\n", "inline.bvh:5: ",
                "twice");
}

TEST(BvhReader, RefusesABadOffsetAndDuplicateNames)
{
    expectError("HIERARCHY\nROOT hips\n{\n OFFSET 0 nan 0\n}\n", "inline.bvh:4: ", "'nan'");
    expectError("HIERARCHY\nROOT a\n{\n OFFSET 0 0 0\n JOINT a\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 0\n"
                "Frame Time: 1\n",
                "inline.bvh:5: ", "a second joint is named 'a'");
}

TEST(BvhReader, RefusesControlCharactersInNamesWithTheLine)
{
    expectError(std::string("HIERARCHY\nROOT hips\n{\n OFFSET 0 0 0\n JOINT chest\0\n", 50), "inline.bvh:5: ",
                "a control character (0x00)");
    expectError("HIERARCHY\nROOT hi\x7fps\n{\n OFFSET 0 0 0\n}\n", "inline.bvh:2: ", "a control character (0x7F)");
}

TEST(BvhReader, RefusesWrongValueCountsAndNonNumbers)
{
    expectError(std::string(kTwoJoints) + "0 0 0 0 0 0 0\n0 0 0 0 0 0\n", "inline.bvh:20: ",
                "frame 1 has 6 values; the hierarchy declares 7");
    expectError(std::string(kTwoJoints) + "0 0 0 0 0 0 0\n0 0 0 nan 0 0 0\n", "inline.bvh:20: ", "'nan'");
    expectError(std::string(kTwoJoints) + "0 0 0 0 0 0 0\n0 0 0 1e999 0 0 0\n", "inline.bvh:20: ", "finite");
}

TEST(BvhReader, RefusesABadMotionHeader)
{
    const std::string hierarchy(kTwoJoints, std::string(kTwoJoints).find("MOTION"));
    expectError(hierarchy + "MOTION\nFrames: 2\nFrame Time: 0\n", "inline.bvh:18: ", "frame time must be positive");
    expectError(hierarchy + "MOTION\nFrames: two\n", "inline.bvh:17: ", "frame count");
    expectError(hierarchy, "inline.bvh:15: ", "before its MOTION");
}

// --- the mapping ---

TEST(BvhReader, MapsChannelsOntoDofsWithTheJointsOwnEulerOrder)
{
    const MocapImport result = readText(std::string(kTwoJoints) + "1 2 3 10 20 30 45\n0 0 0 0 0 0 0\n", fileFrame());
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    ASSERT_EQ(def.getNumJoints(), 2u);
    EXPECT_EQ(def.getEulerOrder(0), EulerOrder::ZXY);
    EXPECT_EQ(def.getTranslationMode(0), TranslationMode::BeforeRotation);
    EXPECT_EQ(def.getDofMask(0), kRotationDofs | kTranslationDofs);
    EXPECT_EQ(def.getDofMask(1), dofBit(Dof::RX));
    // The clip is in DOF-vector order (rx, ry, rz, tx, ty, tz per joint), radians.
    const double deg = glm::pi<double>() / 180.0;
    const double* frame = result.clip->getFrame(0);
    EXPECT_DOUBLE_EQ(frame[def.findDof("hips.rx")], 20 * deg);
    EXPECT_DOUBLE_EQ(frame[def.findDof("hips.ry")], 30 * deg);
    EXPECT_DOUBLE_EQ(frame[def.findDof("hips.rz")], 10 * deg);
    EXPECT_DOUBLE_EQ(frame[def.findDof("hips.ty")], 2.0);
    EXPECT_DOUBLE_EQ(frame[def.findDof("knee.rx")], 45 * deg);
    EXPECT_DOUBLE_EQ(result.clip->getFrameRate(), 2.0);
    EXPECT_EQ(result.clip->getNumFrames(), 2u);
}

TEST(BvhReader, ReadsEndSitesAsJointsWithoutDofsOrLeavesThemOut)
{
    const std::string text = std::string(kTwoJoints) + "0 0 0 0 0 0 0\n0 0 0 0 0 0 0\n";
    BvhImportOptions options = fileFrame();
    options.endSitesAsJoints = true;
    const MocapImport with = readText(text, options);
    ASSERT_TRUE(with) << with.error;
    ASSERT_EQ(with.definition->getNumJoints(), 3u);
    const int end = with.definition->findJoint("knee_end");
    ASSERT_GE(end, 0);
    EXPECT_EQ(with.definition->getDofMask(static_cast<unsigned>(end)), 0);
    EXPECT_TRUE(vectorsNear(with.definition->getOffsetTranslation(static_cast<unsigned>(end)), glm::dvec3(0, -1, 0)));
    EXPECT_EQ(readText(text, fileFrame()).definition->getNumJoints(), 2u);
}

TEST(BvhReader, NamesEndSitesApartFromRealJoints)
{
    // A real joint already named "knee_end": the End Site below the knee takes "knee_end_".
    const std::string text = "HIERARCHY\nROOT knee\n{\n OFFSET 0 0 0\n CHANNELS 1 Xrotation\n JOINT knee_end\n {\n"
                             "  OFFSET 1 0 0\n  CHANNELS 0\n }\n End Site\n {\n  OFFSET 0 1 0\n }\n}\n"
                             "MOTION\nFrames: 1\nFrame Time: 1\n0\n";
    BvhImportOptions options = fileFrame();
    options.endSitesAsJoints = true;
    const MocapImport result = readText(text, options);
    ASSERT_TRUE(result) << result.error;
    EXPECT_GE(result.definition->findJoint("knee_end"), 0);
    const int end = result.definition->findJoint("knee_end_");
    ASSERT_GE(end, 0);
    EXPECT_EQ(result.definition->getDofMask(static_cast<unsigned>(end)), 0);
}

TEST(BvhReader, TakesQuirksOfRealFilesInItsStride)
{
    // CRLF, tabs, trailing spaces, two rotation channels, position channels on a child, .0083 and 1e-014.
    const std::string text = "HIERARCHY\r\nROOT\tpelvis\r\n{\r\n\tOFFSET\t1 2 3 \r\n"
                             "\tCHANNELS 2 Yrotation Xrotation\r\n"
                             "\tJOINT\tneck:1\r\n\t{\r\n\t\tOFFSET 0 .5 0\r\n"
                             "\t\tCHANNELS 4 Xrotation Zposition Zrotation Yposition\r\n"
                             "\t\tEnd Site\r\n\t\t{\r\n\t\t\tOFFSET 0 1 0\r\n\t\t}\r\n\t}\r\n}\r\n"
                             "MOTION\r\nFrames:\t1\r\nFrame Time:\t.0083333\r\n90 1e-014 -0.000000 .5 +90 -.25 \r\n";
    const MocapImport result = readText(text, fileFrame());
    ASSERT_TRUE(result) << result.error;
    const ActorDefinition& def = *result.definition;
    // Inactive axes are skipped, so any order with the listed axes in the listed sequence is exact.
    EXPECT_EQ(def.getEulerOrder(0), EulerOrder::YXZ); // Y then X (Z inactive)
    EXPECT_EQ(def.getEulerOrder(1), EulerOrder::XYZ); // X then Z (Y inactive)
    EXPECT_EQ(def.getDofMask(1), Dof::RX | Dof::RZ | Dof::TY | Dof::TZ);
    EXPECT_NEAR(result.clip->getFrameRate(), 1.0 / 0.0083333, 1e-9);
    // neck origin = T(1,2,3) Ry(90) Rx(0) * (0, .5 + (-.25), .5) = (1,2,3) + Ry(90)(0, .25, .5) = (1.5, 2.25, 3)
    ActorPose pose(result.definition);
    const std::vector<glm::dvec3> origins = posedOrigins(pose, *result.clip, 0);
    EXPECT_TRUE(vectorsNear(origins[0], glm::dvec3(1, 2, 3)));
    EXPECT_TRUE(vectorsNear(origins[1], glm::dvec3(1.5, 2.25, 3), 1e-12));
}

TEST(BvhReader, WarnsWhenTheHeaderFrameCountDisagreesWithTheData)
{
    const std::string three = std::string(kTwoJoints) + "0 0 0 0 0 0 1\n0 0 0 0 0 0 2\n0 0 0 0 0 0 3\n";
    const MocapImport extra = readText(three, fileFrame());
    ASSERT_TRUE(extra) << extra.error;
    EXPECT_EQ(extra.clip->getNumFrames(), 2u) << "the header's count is kept";
    ASSERT_EQ(extra.warnings.size(), 1u);
    EXPECT_NE(extra.warnings[0].find("1 data lines beyond the header's Frames: 2"), std::string::npos);

    const MocapImport missing = readText(std::string(kTwoJoints) + "0 0 0 0 0 0 1\n", fileFrame());
    ASSERT_TRUE(missing) << missing.error;
    EXPECT_EQ(missing.clip->getNumFrames(), 1u);
    ASSERT_EQ(missing.warnings.size(), 1u);
    EXPECT_NE(missing.warnings[0].find("declares 2 frames but the file holds 1"), std::string::npos);
}

TEST(BvhReader, AHeaderClaimingFarMoreFramesThanTheTextHoldsReadsWhatIsThere)
{
    // Room is made for the frames the text may hold, not for the header's count (here about 240 GB of values).
    std::string text = kTwoJoints;
    const std::size_t count = text.find("Frames: 2");
    ASSERT_NE(count, std::string::npos);
    text.replace(count, 9, "Frames: 4294967295");
    const MocapImport read = readText(text + "0 0 0 0 0 0 1\n", fileFrame());
    ASSERT_TRUE(read) << read.error;
    EXPECT_EQ(read.clip->getNumFrames(), 1u);
    ASSERT_EQ(read.warnings.size(), 1u);
    EXPECT_NE(read.warnings[0].find("declares 4294967295 frames but the file holds 1"), std::string::npos);
}

TEST(BvhReader, ScalesTurnsYUpIntoZUpAndDropsTheReferenceFrame)
{
    const std::string text = std::string(kTwoJoints) + "9 9 9 0 0 0 0\n1 2 3 0 0 0 90\n";
    BvhImportOptions options;
    options.scale = 0.5;
    options.dropFirstFrame = true;
    const MocapImport result = readText(text, options);
    ASSERT_TRUE(result) << result.error;
    ASSERT_EQ(result.clip->getNumFrames(), 1u);
    ActorPose pose(result.definition);
    const std::vector<glm::dvec3> origins = posedOrigins(pose, *result.clip, 0);
    // File: hips at (1,2,3), knee 1 below it, end site below the knee turned 90 degrees about X: (1,1,3)+(0,0,-1).
    // Scaled by 0.5 and turned Y-up to Z-up ((x, y, z) -> (x, -z, y)).
    auto toZUp = [](glm::dvec3 p) { return 0.5 * glm::dvec3(p.x, -p.z, p.y); };
    EXPECT_TRUE(vectorsNear(origins[0], toZUp({1, 2, 3}), 1e-12));
    EXPECT_TRUE(vectorsNear(origins[1], toZUp({1, 1, 3}), 1e-12));
    EXPECT_TRUE(vectorsNear(origins[2], toZUp({1, 1, 2}), 1e-12));
}

// --- real files against the reference computation ---

TEST(BvhReader, MatchesTheReferenceOnCmu12_03) { expectMatchesReference(repositoryMocap("bvh/12_03.bvh")); }
TEST(BvhReader, MatchesTheReferenceOnMakeHumanTPose) { expectMatchesReference(repositoryMocap("bvh/tpose.bvh")); }
TEST(BvhReader, MatchesTheReferenceOnAssimp01_01) { expectMatchesReference(assimpBvh("01_01.bvh")); }
TEST(BvhReader, MatchesTheReferenceOnAssimp01_03) { expectMatchesReference(assimpBvh("01_03.bvh")); }
TEST(BvhReader, MatchesTheReferenceOnAssimpBoxingToes) { expectMatchesReference(assimpBvh("Boxing_Toes.bvh")); }
TEST(BvhReader, MatchesTheReferenceWithAbsoluteRootPositions)
{
    expectMatchesReference(assimpBvh("Boxing_Toes.bvh"), true);
}

TEST(BvhReader, KeepsTheHeaderCountOfBoxingToes)
{
    const MocapImport result = readBvhFile(assimpBvh("Boxing_Toes.bvh"), fileFrame());
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(result.clip->getNumFrames(), 3069u);
    ASSERT_EQ(result.warnings.size(), 1u);
    EXPECT_NE(result.warnings[0].find("Boxing_Toes.bvh: 1 data lines beyond"), std::string::npos) << result.warnings[0];
}
