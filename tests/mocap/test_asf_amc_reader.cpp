#include "MocapTestUtil"
#include "ReferenceMocap"

#include <TestMath>

#include <osgActor/mocap/AmcReader>
#include <osgActor/mocap/AsfReader>
#include <osgActor/mocap/MotionFile>

#include <gtest/gtest.h>

#include <glm/ext/scalar_constants.hpp>

#include <algorithm>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const char* const kSmallAsf = ":version 1.10\n:name small\n:units\n  mass 1.0\n  length 0.45\n  angle deg\n"
                              ":root\n   order TX TY TZ RX RY RZ\n   axis XYZ\n   position 0 0 0\n"
                              "   orientation 0 0 0\n"
                              ":bonedata\n  begin\n     id 1\n     name femur\n     direction 0 -1 0\n     length 2\n"
                              "     axis 0 0 90  XYZ\n    dof rx rz\n    limits (-160.0 20.0)\n"
                              "           (-70.0 70.0)\n  end\n"
                              "  begin\n     id 2\n     name tibia\n     direction 0 -1 0\n     length 3\n"
                              "     axis 0 0 0 XYZ\n    dof rx\n    limits (10.0 170.0)\n  end\n"
                              ":hierarchy\n  begin\n    root femur\n    femur tibia\n  end\n";

AsfImport readAsfText(const std::string& text, AsfImportOptions options = AsfImportOptions())
{
    std::istringstream in(text);
    return readAsf(in, "inline.asf", options);
}

AsfImportOptions fileFrame()
{
    AsfImportOptions options;
    options.convertToZUp = false;
    options.applyLimits = false;
    return options;
}

void expectAsfError(const std::string& text, const std::string& fileLine, const std::string& what)
{
    const AsfImport result = readAsfText(text);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.definition, nullptr);
    EXPECT_EQ(result.error.rfind(fileLine, 0), 0u) << result.error;
    EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

void expectAmcError(const std::string& text, const std::string& fileLine, const std::string& what)
{
    const AsfImport skeleton = readAsfText(kSmallAsf, fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    std::istringstream in(text);
    const MocapImport result = readAmc(in, "inline.amc", skeleton);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.clip, nullptr);
    EXPECT_EQ(result.error.rfind(fileLine, 0), 0u) << result.error;
    EXPECT_NE(result.error.find(what), std::string::npos) << result.error;
}

/** Our import of a real pair against the reference computation, at several frames, to 1e-6 of its size. */
void expectMatchesReference(const std::string& asfPath, const std::string& amcPath)
{
    SCOPED_TRACE(amcPath);
    const AsfImport skeleton = readAsfFile(asfPath, fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    const MocapImport motion = readAmcFile(amcPath, skeleton);
    ASSERT_TRUE(motion) << motion.error;
    EXPECT_TRUE(motion.warnings.empty());
    const reference::Asf asf = reference::readAsf(asfPath);
    const std::vector<reference::AmcFrame> frames = reference::readAmc(amcPath);
    ASSERT_EQ(motion.clip->getNumFrames(), frames.size());
    EXPECT_DOUBLE_EQ(motion.clip->getFrameRate(), 120.0);

    ActorPose pose(motion.definition);
    const unsigned last = motion.clip->getNumFrames() - 1;
    std::vector<glm::dvec3> rest;
    for (const auto& entry : reference::asfPositions(asf, frames[0])) rest.push_back(entry.second);
    const double size = extent(rest);
    ASSERT_GT(size, 0.0);
    for (unsigned frame : {0u, 1u, last / 3, last / 2, last})
    {
        SCOPED_TRACE("frame " + std::to_string(frame));
        const std::map<std::string, glm::dvec3> expected = reference::asfPositions(asf, frames[frame]);
        const std::vector<glm::dvec3> actual = posedOrigins(pose, *motion.clip, frame);
        ASSERT_EQ(expected.size(), actual.size());
        for (const auto& entry : expected)
        {
            const int joint = motion.definition->findJoint(entry.first);
            ASSERT_GE(joint, 0) << entry.first;
            EXPECT_TRUE(vectorsNear(actual[static_cast<unsigned>(joint)], entry.second, 1e-6 * size)) << entry.first;
        }
    }
}

} // namespace

// --- invalid input first ---

TEST(AsfReader, RefusesAMissingFileAndMissingSections)
{
    EXPECT_NE(readAsfFile("/nonexistent/a.asf").error.find("/nonexistent/a.asf: cannot open"), std::string::npos);
    expectAsfError(":version 1.10\n:hierarchy\nbegin\nend\n", "inline.asf:4: ", "no :root");
    expectAsfError(":root\n order TX TY TZ RX RY RZ\n axis XYZ\n", "inline.asf:3: ", "no :hierarchy");
}

TEST(AsfReader, RefusesBrokenBones)
{
    std::string text = kSmallAsf;
    expectAsfError(std::string(text).replace(text.find("length 2"), 8, "length -2"), "inline.asf:17: ",
                   "length of 'femur'");
    expectAsfError(std::string(text).replace(text.find("dof rx rz"), 9, "dof rx rw"), "inline.asf:19: ",
                   "dof 'rw' of 'femur'");
    expectAsfError(std::string(text).replace(text.find("dof rx rz"), 9, "dof rx l"), "inline.asf:19: ",
                   "dof 'l' (stretching) of 'femur' is not supported");
    expectAsfError(std::string(text).replace(text.find("axis 0 0 90  XYZ"), 16, "axis 0 nan 90 XYZ"),
                   "inline.asf:18: ", "'nan'");
    expectAsfError(std::string(text).replace(text.find("femur tibia"), 11, "femur fibula"), "inline.asf:35: ",
                   "unknown bone 'fibula'");
    expectAsfError(std::string(text).replace(text.find("(-70.0 70.0)"), 12, "(70.0 -70.0)"), "inline.asf:21: ",
                   "minimum above its maximum");
    expectAsfError(std::string(kSmallAsf, text.find("  end\n  begin")), "inline.asf:21: ", "missing 'end'");
}

TEST(AmcReader, RefusesUnknownBonesWrongCountsAndNonNumbers)
{
    expectAmcError(":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\nfibula 1\n", "inline.amc:5: ",
                   "unknown bone 'fibula'");
    expectAmcError("1\nroot 0 0 0 0 0 0\nfemur 1\n", "inline.amc:3: ", "bone 'femur' has 1 values; its dof list has 2");
    expectAmcError("1\nroot 0 0 0 0 0 0\nfemur 1 nan\n", "inline.amc:3: ", "'nan'");
    expectAmcError("root 0 0 0 0 0 0\n", "inline.amc:1: ", "before the first frame number");
    expectAmcError(":DEGREES\n", "inline.amc:1: ", "no frame");
}

TEST(AmcReader, RefusesFrameNumbersThatGoBackRepeatOrJump)
{
    // Frames are stored one after the other at the frame rate: a renumbering would move every later frame in time.
    const std::string frame = "root 0 0 0 0 0 0\nfemur 1 2\ntibia 3\n";
    expectAmcError("1\n" + frame + "2\n" + frame + "1\n" + frame, "inline.amc:9: ",
                   "frame number 1 follows frame 2; AMC frames must be numbered one after the other");
    expectAmcError("7\n" + frame + "7\n" + frame, "inline.amc:5: ", "frame number 7 follows frame 7");
    expectAmcError("1\n" + frame + "3\n" + frame, "inline.amc:5: ", "frame number 3 follows frame 1");
    expectAmcError("18446744073709551615\n" + frame + "0\n" + frame, "inline.amc:5: ",
                   "frame number 0 follows frame 18446744073709551615");
    // Any first number, then one more each frame.
    const AsfImport skeleton = readAsfText(kSmallAsf, fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    std::istringstream in("0\n" + frame + "1\n" + frame + "2\n" + frame);
    const MocapImport motion = readAmc(in, "inline.amc", skeleton);
    ASSERT_TRUE(motion) << motion.error;
    EXPECT_EQ(motion.clip->getNumFrames(), 3u);
}

TEST(AsfAmc, ControlCharactersInNamesAreRefusedWithTheLine)
{
    std::string asf = kSmallAsf;
    asf.replace(asf.find("name femur"), 10, std::string("name fe\0mur", 12));
    expectAsfError(asf, "inline.asf:15: ", "a control character (0x00)");
    expectAmcError("1\nroot 0 0 0 0 0 0\nfemur\x1b 1 2\n", "inline.amc:3: ", "a control character (0x1B)");
}

// --- the mapping ---

TEST(AsfReader, MapsBonesAxesDofsAndLimitsOntoJoints)
{
    const AsfImport skeleton = readAsfText(kSmallAsf);
    ASSERT_TRUE(skeleton) << skeleton.error;
    const ActorDefinition& def = *skeleton.definition;
    EXPECT_DOUBLE_EQ(skeleton.lengthUnit, 0.45);
    ASSERT_EQ(def.getNumJoints(), 3u);
    EXPECT_EQ(def.getJointName(0), "root");
    EXPECT_EQ(def.getDofMask(0), kRotationDofs | kTranslationDofs);
    EXPECT_EQ(def.getEulerOrder(0), EulerOrder::ZYX) << "RX RY RZ, first applied first, is Rz * Ry * Rx";
    const unsigned femur = static_cast<unsigned>(def.findJoint("femur"));
    EXPECT_EQ(def.getDofMask(femur), Dof::RX | Dof::RZ);
    // rx rz, first applied first, is Rz * Rx: any order with Z left of X (the Y rotation is inactive).
    unsigned axes[3];
    eulerOrderAxes(def.getEulerOrder(femur), axes);
    const auto at = [&](unsigned axis) { return std::find(axes, axes + 3, axis) - axes; };
    EXPECT_LT(at(2), at(0));
    const double deg = glm::pi<double>() / 180.0;
    const int femurRz = def.getDofIndex(femur, Dof::RZ);
    EXPECT_DOUBLE_EQ(def.getDofMin(static_cast<unsigned>(femurRz)), -70 * deg);
    EXPECT_DOUBLE_EQ(def.getDofMax(static_cast<unsigned>(femurRz)), 70 * deg);
    // tibia's limits (10, 170) exclude 0: its rest value is the nearest limit.
    const int tibiaRx = def.findDof("tibia.rx");
    EXPECT_DOUBLE_EQ(def.getDofDefault(static_cast<unsigned>(tibiaRx)), 10 * deg);
    // tibia starts at the femur's end: 2 along the femur's direction, in the femur's axis frame (C = Rz(90)).
    const unsigned tibia = static_cast<unsigned>(def.findJoint("tibia"));
    EXPECT_TRUE(vectorsNear(def.getOffsetTranslation(tibia), glm::dvec3(-2, 0, 0), 1e-12));
}

TEST(AmcReader, AppliesTheDofOrderUnitsAndHeldValues)
{
    const AsfImport skeleton = readAsfText(kSmallAsf, fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    // Frame 2 leaves out the tibia: it keeps frame 1's value (with a warning).
    std::istringstream in("#!OML:ASF small.asf\n:FULLY-SPECIFIED\n:RADIANS\n1\nroot 1 2 3 0 0 0\nfemur 0.5 0.25\n"
                          "tibia 1.5\n2\nroot 0 0 0 0 0 0\nfemur 0 0\n");
    const MocapImport motion = readAmc(in, "inline.amc", skeleton);
    ASSERT_TRUE(motion) << motion.error;
    ASSERT_EQ(motion.clip->getNumFrames(), 2u);
    EXPECT_EQ(motion.warnings.size(), 1u);
    const ActorDefinition& def = *motion.definition;
    const double* f0 = motion.clip->getFrame(0);
    EXPECT_DOUBLE_EQ(f0[def.findDof("root.ty")], 2.0);
    EXPECT_DOUBLE_EQ(f0[def.findDof("femur.rx")], 0.5);
    EXPECT_DOUBLE_EQ(f0[def.findDof("femur.rz")], 0.25);
    EXPECT_DOUBLE_EQ(motion.clip->getFrame(1)[def.findDof("tibia.rx")], 1.5);
}

TEST(AsfReader, ScalesAndTurnsYUpIntoZUp)
{
    AsfImportOptions options;
    options.scale = 0.5;
    options.applyLimits = false;
    const AsfImport skeleton = readAsfText(kSmallAsf, options);
    ASSERT_TRUE(skeleton) << skeleton.error;
    std::istringstream in("1\nroot 1 2 3 0 0 0\nfemur 0 0\ntibia 0\n");
    const MocapImport motion = readAmc(in, "inline.amc", skeleton);
    ASSERT_TRUE(motion) << motion.error;
    ActorPose pose(motion.definition);
    const std::vector<glm::dvec3> origins = posedOrigins(pose, *motion.clip, 0);
    // File frame: root (1,2,3); the femur points down 2, so the tibia starts at (1,0,3). Scaled, Z-up.
    EXPECT_TRUE(vectorsNear(origins[0], glm::dvec3(0.5, -1.5, 1.0), 1e-12));
    EXPECT_TRUE(vectorsNear(origins[2], glm::dvec3(0.5, -1.5, 0.0), 1e-12));
}

TEST(AsfReader, TakesBoneTranslationsInTheBoneAxisFrameInLengthUnits)
{
    AsfImportOptions options = fileFrame();
    options.applyLimits = true;
    options.scale = 2.0;
    const AsfImport scaled = readAsfFile(testData("sliding.asf"), options);
    ASSERT_TRUE(scaled) << scaled.error;
    const ActorDefinition& def = *scaled.definition;
    const unsigned femur = static_cast<unsigned>(def.findJoint("femur"));
    EXPECT_EQ(def.getDofMask(femur), Dof::RX | Dof::TY | Dof::RZ);
    EXPECT_EQ(def.getTranslationMode(femur), TranslationMode::BeforeRotation);
    // Limits follow each dof's unit: the translation's are lengths (times scale), the rotations' degrees.
    const unsigned femurTy = static_cast<unsigned>(def.findDof("femur.ty"));
    EXPECT_DOUBLE_EQ(def.getDofMin(femurTy), -1.0);
    EXPECT_DOUBLE_EQ(def.getDofMax(femurTy), 1.0);
    EXPECT_DOUBLE_EQ(def.getDofMax(static_cast<unsigned>(def.findDof("femur.rz"))), 170.0 * glm::pi<double>() / 180);

    const AsfImport skeleton = readAsfFile(testData("sliding.asf"), fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    const MocapImport motion = readAmcFile(testData("sliding.amc"), skeleton);
    ASSERT_TRUE(motion) << motion.error;
    const ActorDefinition& motionDef = *motion.definition;
    const unsigned tibia = static_cast<unsigned>(motionDef.findJoint("tibia")),
                   foot = static_cast<unsigned>(motionDef.findJoint("foot"));
    ActorPose pose(motion.definition);
    // Frame 1: the femur points down 2 and is still. The tibia's (0.5, 0.25, 0) is in its axis frame, C = Rz(90):
    // (-0.25, 0.5, 0) in the file's, so it starts at (0, -2, 0) + that and ends 3 lower.
    std::vector<glm::dvec3> origins = posedOrigins(pose, *motion.clip, 0);
    EXPECT_TRUE(vectorsNear(origins[tibia], glm::dvec3(-0.25, -1.5, 0), 1e-12));
    EXPECT_TRUE(vectorsNear(origins[foot], glm::dvec3(-0.25, -4.5, 0), 1e-12));
    // Frame 2: the femur turns 90 degrees about Z, so it ends at (2, 0, 0) and the tibia's translation turns with it
    // (C = Rz(90) after Rz(90): (-0.5, -0.25, 0)). The tibia's own rx 90 (about its C's x, the file's y) does not move
    // its start, only its end: W = Rz(90) Ry(90) takes (0, -3, 0) to (3, 0, 0).
    origins = posedOrigins(pose, *motion.clip, 1);
    EXPECT_TRUE(vectorsNear(origins[tibia], glm::dvec3(1.5, -0.25, 0), 1e-12));
    EXPECT_TRUE(vectorsNear(origins[foot], glm::dvec3(4.5, -0.25, 0), 1e-12));
    // The translations are lengths: scaled with the skeleton.
    const MocapImport scaledMotion = readAmcFile(testData("sliding.amc"), scaled);
    ASSERT_TRUE(scaledMotion) << scaledMotion.error;
    ActorPose scaledPose(scaledMotion.definition);
    EXPECT_TRUE(vectorsNear(posedOrigins(scaledPose, *scaledMotion.clip, 0)[tibia], glm::dvec3(-0.5, -3, 0), 1e-12));
}

// --- real files against the reference computation ---

TEST(AsfAmc, MatchesTheReferenceOnCmuSubject11)
{
    expectMatchesReference(repositoryMocap("asfamc/11.asf"), repositoryMocap("asfamc/11_01.amc"));
}

TEST(AsfAmc, MatchesTheReferenceOnCharleston)
{
    expectMatchesReference(repositoryMocap("asfamc/charleston.asf"), repositoryMocap("asfamc/charleston1.amc"));
}

TEST(AsfAmc, MatchesTheReferenceOnBonesThatTranslate)
{
    expectMatchesReference(testData("sliding.asf"), testData("sliding.amc"));
}

TEST(AsfAmc, ReadsSeveralMotionsAgainstOneSkeleton)
{
    const AsfImport skeleton = readAsfFile(repositoryMocap("asfamc/11.asf"), fileFrame());
    ASSERT_TRUE(skeleton) << skeleton.error;
    const MocapImport first = readAmcFile(repositoryMocap("asfamc/11_01.amc"), skeleton);
    std::istringstream in("1\nroot 0 0 0 0 0 0\n");
    const MocapImport second = readAmc(in, "still.amc", skeleton);
    ASSERT_TRUE(first) << first.error;
    ASSERT_TRUE(second) << second.error;
    EXPECT_EQ(first.definition, second.definition) << "one shared definition";
    EXPECT_EQ(second.clip->getName(), "still");
}

TEST(MotionFile, ReadsAnAmcAgainstItsSkeletonUnderTheGivenNameWithTheGivenOptions)
{
    MotionFileOptions options;
    options.name = "run";
    options.skeletonFile = repositoryMocap("asfamc/11.asf");
    options.scale = 0.5;
    options.amcFrameRate = 60.0;
    const MocapImport motion = readMotionFile(repositoryMocap("asfamc/11_01.amc"), options);
    ASSERT_TRUE(motion) << motion.error;
    ASSERT_TRUE(motion.clip);
    EXPECT_EQ(motion.clip->getName(), "run");
    EXPECT_EQ(motion.clip->getFrameRate(), 60.0);

    AsfImportOptions asf;
    asf.scale = 0.5;
    asf.applyLimits = false;
    const AsfImport skeleton = readAsfFile(repositoryMocap("asfamc/11.asf"), asf);
    ASSERT_TRUE(skeleton) << skeleton.error;
    const MocapImport direct = readAmcFile(repositoryMocap("asfamc/11_01.amc"), skeleton);
    ASSERT_TRUE(direct) << direct.error;
    ASSERT_EQ(motion.clip->getNumFrames(), direct.clip->getNumFrames());
    ASSERT_EQ(motion.clip->getNumChannels(), direct.clip->getNumChannels());
    // The root's translation, scaled: the same values frame by frame.
    const int rootX = motion.definition->findDof("root.tx");
    ASSERT_GE(rootX, 0);
    for (unsigned f : {0u, 100u})
        EXPECT_EQ(motion.clip->getFrame(f)[rootX], direct.clip->getFrame(f)[rootX]) << "frame " << f;
    EXPECT_NE(motion.clip->getFrame(0)[rootX], 0.0);
}

TEST(MotionFile, RefusesAnAmcWithoutSkeletonAndOtherFormats)
{
    MocapImport motion = readMotionFile(repositoryMocap("asfamc/11_01.amc"), MotionFileOptions());
    EXPECT_FALSE(motion);
    EXPECT_NE(motion.error.find("11_01.amc: an AMC motion needs the ASF skeleton"), std::string::npos) << motion.error;
    motion = readMotionFile("walk.fbx", MotionFileOptions());
    EXPECT_FALSE(motion);
    EXPECT_EQ(motion.error, "walk.fbx: not a motion file (expected .bvh, or .amc with its ASF skeleton)");
    MotionFileOptions broken;
    broken.skeletonFile = "/nonexistent/11.asf";
    motion = readMotionFile(repositoryMocap("asfamc/11_01.amc"), broken);
    EXPECT_FALSE(motion);
    EXPECT_NE(motion.error.find("/nonexistent/11.asf: cannot open"), std::string::npos) << motion.error;
}
