// osgactorrender --compare end to end: the deliberately changed scene (tests/render/scenes/two_boxes_changed.osgt,
// the right box red instead of white) against the references of the unchanged one; the diff images must show the
// change where it is, and nowhere else.
#include <osgActor/Offscreen/ImageComparison>
#include <osgActor/Offscreen/OffscreenRenderer>

#include <osgDB/FileUtils>

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

using namespace osgActor;

namespace {

const std::string kScenes = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/render/scenes/";
const std::string kReferences = std::string(OSGACTOR_TEST_SOURCE_DIR) + "/render/references/two_boxes_%04d.png";
const std::string kOut = std::string(OSGACTOR_TEST_BINARY_DIR) + "/compare_command/";
// The frames the references hold: 4 frames, 2 per second, 160 x 120, from this camera.
const std::string kFrames = " --frames 0 3 --fps 2 --size 160 120 --eye 0 -6 2.5 --center 0 0 0";
const osg::Vec3d kEye(0.0, -6.0, 2.5);

/** Runs osgactorrender with the arguments; its exit status (-1 if it did not exit), its output in output. */
int runRender(const std::string& arguments, std::string& output)
{
    // One log per test: ctest runs the tests of this file at the same time.
    const std::string log = kOut + ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".log";
    osgDB::makeDirectoryForFile(log);
    const int status = std::system((std::string(OSGACTOR_TEST_PROGRAM_DIR) + "/osgactorrender" + arguments + " > " + log + " 2>&1").c_str());
    std::ifstream in(log);
    std::ostringstream text;
    text << in.rdbuf();
    output = text.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/** Where a world point lands in the images of the references' camera, as integer pixel coordinates. */
void project(const osg::Vec3d& world, int& x, int& y)
{
    std::string error;
    const osg::ref_ptr<OffscreenRenderer> renderer = OffscreenRenderer::create(160, 120, error);
    ASSERT_TRUE(renderer.valid()) << error;
    renderer->setViewMatrixAsLookAt(kEye, osg::Vec3d(0, 0, 0), osg::Vec3d(0, 0, 1));
    const osg::Vec3d window = renderer->projectToWindow(world);
    x = int(window.x());
    y = int(window.y());
}

osg::ref_ptr<osg::Image> readImage(const std::string& file)
{
    std::string error;
    osg::ref_ptr<osg::Image> image = readRgbImage(file, error);
    EXPECT_TRUE(image.valid()) << error;
    return image;
}

std::string frameFile(const std::string& pattern, unsigned frame)
{
    char name[512];
    std::snprintf(name, sizeof name, pattern.c_str(), frame);
    return name;
}

} // namespace

TEST(CompareCommand, AnUnchangedSceneMatchesOnEveryRun)
{
    for (int run = 0; run < 3; ++run)
    {
        std::string output;
        EXPECT_EQ(runRender(" " + kScenes + "two_boxes.osgt" + kFrames + " --compare " + kReferences, output), 0)
            << output;
        EXPECT_NE(output.find("all 4 frames match"), std::string::npos) << output;
        EXPECT_NE(output.find("largest difference 0, lowest PSNR inf dB"), std::string::npos) << output;
    }
}

TEST(CompareCommand, AChangedSceneFailsWithADiffImageThatShowsTheChange)
{
    const std::string out = kOut + "changed/";
    std::string output;
    const int status = runRender(" " + kScenes + "two_boxes_changed.osgt" + kFrames + " --compare " + kReferences +
                                     " --diff " + out + "diff_%04d.png --compare-sheet " + out + "sheet.png",
                                 output);
    EXPECT_EQ(status, 1) << output;
    EXPECT_NE(output.find("4 of 4 frames differ"), std::string::npos) << output;
    for (unsigned frame = 0; frame < 4; ++frame)
        EXPECT_NE(output.find("frame " + std::to_string(frame) + " differs from"), std::string::npos) << output;

    // The right box (the changed one) is red in every diff; the left box, which turns but did not change, is the
    // reference dimmed to a third.
    int rightX = 0, rightY = 0, leftX = 0, leftY = 0;
    project(osg::Vec3d(1.2, 0.0, 0.0), rightX, rightY);
    project(osg::Vec3d(-1.2, 0.0, 0.0), leftX, leftY);
    ASSERT_GT(rightX, leftX);
    for (unsigned frame = 0; frame < 4; ++frame)
    {
        const osg::ref_ptr<osg::Image> diff = readImage(frameFile(out + "diff_%04d.png", frame));
        const osg::ref_ptr<osg::Image> reference = readImage(frameFile(kReferences, frame));
        ASSERT_TRUE(diff.valid() && reference.valid());
        const unsigned char* changed = diff->data(rightX, rightY);
        EXPECT_GE(int(changed[0]), 128) << "frame " << frame;
        EXPECT_EQ(int(changed[1]), 0) << "frame " << frame;
        EXPECT_EQ(int(changed[2]), 0) << "frame " << frame;
        const unsigned char* same = diff->data(leftX, leftY);
        const unsigned char* referencePixel = reference->data(leftX, leftY);
        EXPECT_GT(int(referencePixel[0]), 100) << "the left box is white in the reference";
        for (int c = 0; c < 3; ++c) EXPECT_EQ(int(same[c]), referencePixel[c] / 3) << "frame " << frame;
    }

    // One row per differing frame: reference, render, diff, each 160 x 120 with 4-pixel margins.
    const osg::ref_ptr<osg::Image> sheet = readImage(out + "sheet.png");
    ASSERT_TRUE(sheet.valid());
    EXPECT_EQ(sheet->s(), 3 * (160 + 4) + 4);
    EXPECT_EQ(sheet->t(), 4 * (120 + 4) + 4);
}

TEST(CompareCommand, TwoProcessesReportAndDrawTheSameDifferences)
{
    const std::string one = kOut + "jobs1/";
    const std::string two = kOut + "jobs2/";
    std::string output1, output2;
    const std::string compare =
        " " + kScenes + "two_boxes_changed.osgt" + kFrames + " --compare " + kReferences + " --report ";
    // No -o: the comparison sheet reads the differing renders back from a temporary folder.
    EXPECT_EQ(runRender(compare + one + "report.csv --diff " + one + "d_%04d.png --compare-sheet " + one + "sheet.png",
                        output1),
              1)
        << output1;
    EXPECT_EQ(runRender(compare + two + "report.csv --diff " + two + "d_%04d.png --compare-sheet " + two +
                            "sheet.png --jobs 2",
                        output2),
              1)
        << output2;
    EXPECT_NE(output2.find("2 processes"), std::string::npos) << output2;
    for (unsigned frame = 0; frame < 4; ++frame)
    {
        const osg::ref_ptr<osg::Image> a = readImage(frameFile(one + "d_%04d.png", frame));
        const osg::ref_ptr<osg::Image> b = readImage(frameFile(two + "d_%04d.png", frame));
        ASSERT_TRUE(a.valid() && b.valid());
        EXPECT_EQ(compareImages(*a, *b, 0).maxChannelDifference, 0) << "frame " << frame;
    }
    const osg::ref_ptr<osg::Image> sheet1 = readImage(one + "sheet.png");
    const osg::ref_ptr<osg::Image> sheet2 = readImage(two + "sheet.png");
    ASSERT_TRUE(sheet1.valid() && sheet2.valid());
    EXPECT_EQ(compareImages(*sheet1, *sheet2, 0).maxChannelDifference, 0);
    std::ifstream report1(one + "report.csv"), report2(two + "report.csv");
    std::stringstream text1, text2;
    text1 << report1.rdbuf();
    text2 << report2.rdbuf();
    EXPECT_EQ(text1.str(), text2.str());
    EXPECT_NE(text1.str().find("3,differs,"), std::string::npos) << text1.str();
}
