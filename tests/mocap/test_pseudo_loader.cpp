#include "MocapActorCheck"

#include <osgActor/ActorNode>
#include <osgActor/ActorSceneIO>
#include <osgActor/core/ClipPlayer>
#include <osgActor/io/ActorDocument>
#include <osgActor/io/ActorWriter>
#include <osgActor/mocap/AsfReader>
#include <osgActor/mocap/BvhReader>

#include <osgDB/FileNameUtils>
#include <osgDB/FileUtils>
#include <osgDB/ReadFile>
#include <osgDB/Registry>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** Reads through osgDB's registry (plugin lookup by the last extension, .actor), as osgviewer does. */
osgDB::ReaderWriter::ReadResult readThroughOsgDB(const std::string& file, const std::string& optionString = "")
{
    osg::ref_ptr<osgDB::Options> options = new osgDB::Options(optionString);
    return osgDB::Registry::instance()->readNode(file, options.get());
}

/** The actor a .actor file with a clip named "walk" gives through osgDB, with that clip; the test fails (and clip
  * stays null) when the file does not read or lacks the clip. */
void readActorWithWalkClip(const std::string& path, osg::ref_ptr<ActorNode>& actor, ClipPtr& clip)
{
    osgDB::ReaderWriter::ReadResult read = readThroughOsgDB(path);
    ASSERT_TRUE(read.validNode()) << read.message();
    actor = dynamic_cast<ActorNode*>(read.getNode());
    ASSERT_TRUE(actor.valid() && actor->getClipLibrary());
    clip = actor->getClipLibrary()->getClip("walk");
    ASSERT_TRUE(clip) << path << ": named as in the .actor file, not after the motion file";
}

/** Writes document as folderName/walker.actor, with copies of the given files of data/mocap in
  * folderName/motion; returns the .actor file's path. */
std::string writeActorBesideMotionFiles(const std::string& folderName, const ActorDocument& document,
                                        const std::vector<std::string>& mocapFiles)
{
    const std::string folder = std::string(OSGACTOR_TEST_BINARY_DIR) + "/" + folderName;
    osgDB::makeDirectory(folder + "/motion");
    for (const std::string& file : mocapFiles)
    {
        std::ifstream in(repositoryMocap(file), std::ios::binary);
        std::ofstream out(folder + "/motion/" + osgDB::getSimpleFileName(file), std::ios::binary);
        out << in.rdbuf();
    }
    const std::string path = folder + "/walker.actor";
    std::ofstream out(path);
    writeActor(out, document);
    return path;
}

/** A clip "walk", played in a loop, whose motion is the file at fileReference, read with options. */
ClipDocument walkFromFile(const std::string& fileReference, MotionFileOptions options = MotionFileOptions())
{
    ClipDocument clip;
    clip.file = fileReference;
    clip.fileOptions = std::move(options);
    clip.fileOptions.name = "walk";
    clip.play = true;
    return clip;
}

/** Writes, in its own folder, 12_03.bvh's skeleton as a .actor file whose clip "walk" (played in a loop) refers to
  * the file by fileReference, with a copy of the file beside it; returns the .actor file's path. edit changes the
  * document first. */
template <class Edit>
std::string writeActorWithClipFile(const std::string& folderName, const std::string& fileReference, Edit edit)
{
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/12_03.bvh"));
    EXPECT_TRUE(imported) << imported.error;
    ActorDocument document = makeDocument(*imported.definition);
    document.clips.push_back(walkFromFile(fileReference));
    edit(document);
    return writeActorBesideMotionFiles(folderName, document, {"bvh/12_03.bvh"});
}

} // namespace

TEST(MocapPseudoLoader, ReportsMissingAndBrokenFiles)
{
    EXPECT_EQ(readThroughOsgDB("/nonexistent/walk.bvh.actor").status(),
              osgDB::ReaderWriter::ReadResult::FILE_NOT_FOUND);

    const std::string broken = std::string(OSGACTOR_TEST_BINARY_DIR) + "/pseudo_broken.bvh";
    std::ofstream(broken) << "HIERARCHY\nROOT hips\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Xrotation\n}\nMOTION\nFrames: 1\n"
                             "Frame Time: 0.1\n1 2\n";
    osgDB::ReaderWriter::ReadResult result = readThroughOsgDB(broken + ".actor");
    EXPECT_FALSE(result.validNode());
    EXPECT_NE(result.message().find("pseudo_broken.bvh:10: frame 0 has 2 values"), std::string::npos)
        << result.message();

    osgDB::ReaderWriter::ReadResult badOption = readThroughOsgDB(repositoryMocap("bvh/tpose.bvh.actor"), "scale=big");
    EXPECT_FALSE(badOption.validNode());
    EXPECT_NE(badOption.message().find("scale needs a positive number"), std::string::npos) << badOption.message();

    osgDB::ReaderWriter::ReadResult noAmc = readThroughOsgDB(repositoryMocap("asfamc/11.asf.actor"), "amc=nothing.amc");
    EXPECT_FALSE(noAmc.validNode());
    EXPECT_NE(noAmc.message().find("cannot find the AMC file 'nothing.amc'"), std::string::npos) << noAmc.message();
}

TEST(MocapPseudoLoader, LoadsABvhFileAsAPlayingActor)
{
    osgDB::ReaderWriter::ReadResult result = readThroughOsgDB(repositoryMocap("bvh/12_03.bvh.actor"));
    ASSERT_TRUE(result.validNode()) << result.message();
    ActorNode* actor = dynamic_cast<ActorNode*>(result.getNode());
    ASSERT_NE(actor, nullptr);
    EXPECT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(actor->findController("mocap")));
    // Posed at frame 0 at once, in OSG's Z-up frame.
    const reference::Bvh bvh = reference::readBvh(repositoryMocap("bvh/12_03.bvh"));
    const std::vector<glm::dvec3> expected = reference::bvhPositions(bvh, 0);
    const double size = extent(expected);
    for (std::size_t j = 0; j < bvh.joints.size(); ++j)
    {
        if (bvh.joints[j].endSite) continue;
        const int joint = actor->getJointIndex(bvh.joints[j].name);
        ASSERT_GE(joint, 0);
        EXPECT_LT((actor->getJointWorldPosition(static_cast<unsigned>(joint)) - zUp(expected[j])).length(),
                  1e-6 * size);
    }
}

TEST(MocapPseudoLoader, LoadsAnAsfWithItsAmcNamedOrFound)
{
    osgDB::ReaderWriter::ReadResult found = readThroughOsgDB(repositoryMocap("asfamc/charleston.asf.actor"));
    ASSERT_TRUE(found.validNode()) << found.message();
    osgDB::ReaderWriter::ReadResult named =
        readThroughOsgDB(repositoryMocap("asfamc/11.asf.actor"), "amc=11_01.amc fps=60 rootMotion=in_place");
    ASSERT_TRUE(named.validNode()) << named.message();
    ActorNode* actor = dynamic_cast<ActorNode*>(named.getNode());
    ASSERT_NE(actor, nullptr);
    auto player = std::dynamic_pointer_cast<ClipPlayer>(actor->findController("mocap"));
    ASSERT_TRUE(player);
    EXPECT_DOUBLE_EQ(player->getClip()->getFrameRate(), 60.0);
    EXPECT_EQ(player->getRootMotion(), RootMotion::InPlace);
}

TEST(ActorFileClips, AnActorFileCarriesAndPlaysItsMotion)
{
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/12_03.bvh"));
    ASSERT_TRUE(imported) << imported.error;
    ActorDocument document = makeDocument(*imported.definition);
    document.name = "walker";
    ClipDocument clip;
    clip.clip = imported.clip;
    clip.play = true;
    document.clips.push_back(clip);
    const std::string path = std::string(OSGACTOR_TEST_BINARY_DIR) + "/walker.actor";
    {
        std::ofstream out(path);
        writeActor(out, document);
    }
    osgDB::ReaderWriter::ReadResult read = readThroughOsgDB(path);
    ASSERT_TRUE(read.validNode()) << read.message();
    osg::ref_ptr<ActorNode> actor = dynamic_cast<ActorNode*>(read.getNode());
    ASSERT_TRUE(actor.valid());
    ASSERT_TRUE(actor->getClipLibrary());
    EXPECT_TRUE(actor->getClipLibrary()->getClip("12_03"));
    ASSERT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(actor->findController("12_03")));

    expectToFollowBvh(*actor, repositoryMocap("bvh/12_03.bvh"), {0u, 5u}, false);
}

TEST(ActorFileClips, ABrokenClipSectionFailsTheRead)
{
    const std::string path = std::string(OSGACTOR_TEST_BINARY_DIR) + "/broken_clip.actor";
    std::ofstream(path) << "osgactor 1\nactor a {\n    joint b {\n        dof rx\n    }\n    clip wave {\n"
                           "        channel b.rx {\n            key 0 nan\n        }\n    }\n}\n";
    osgDB::ReaderWriter::ReadResult read = readThroughOsgDB(path);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("broken_clip.actor:8: "), std::string::npos) << read.message();
}

TEST(ActorFileClips, AClipReadFromABvhFileBesideTheActorFilePlaysTheFile)
{
    const std::string path = writeActorWithClipFile("clip_file", "motion/12_03.bvh", [](ActorDocument&) {});
    osg::ref_ptr<ActorNode> actor;
    ClipPtr clip;
    readActorWithWalkClip(path, actor, clip);
    ASSERT_TRUE(clip);
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/12_03.bvh"));
    EXPECT_EQ(clip->getNumFrames(), imported.clip->getNumFrames());
    ASSERT_TRUE(std::dynamic_pointer_cast<ClipPlayer>(actor->findController("walk")));
    expectToFollowBvh(*actor, repositoryMocap("bvh/12_03.bvh"), {0u, 5u}, false);

    // The actor holds the motion, not where it came from: written out, the clip is frames.
    std::ostringstream written;
    writeActor(written, extractActorDocument(*actor));
    EXPECT_NE(written.str().find("clip walk {\n        frame_rate 120"), std::string::npos);
    EXPECT_NE(written.str().find("player walk {\n        clip walk\n        play loop\n"), std::string::npos)
        << "the player the clip's play statement made";
    EXPECT_EQ(written.str().find("file \""), std::string::npos);
}

TEST(ActorFileClips, AClipFileMissingOrNotFittingTheActorFailsTheReadAtItsLine)
{
    const auto clipLine = [](const std::string& path) {
        std::ifstream in(path);
        std::string line;
        for (int number = 1; std::getline(in, line); ++number)
            if (line.find("clip walk") != std::string::npos) return number;
        return 0;
    };

    const std::string missing = writeActorWithClipFile("clip_file_missing", "motion/nowhere.bvh", [](ActorDocument&) {});
    osgDB::ReaderWriter::ReadResult read = readThroughOsgDB(missing);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("walker.actor:" + std::to_string(clipLine(missing)) +
                                  ": clip 'walk': cannot find the motion file 'motion/nowhere.bvh'"),
              std::string::npos)
        << read.message();

    // The file's LeftUpLeg turns in ZYX order (12_03.bvh's channels); the actor's, given another order, would read
    // the same three angles as another rotation.
    const std::string misfit = writeActorWithClipFile("clip_file_misfit", "motion/12_03.bvh", [](ActorDocument& d) {
        for (JointDocument& joint : d.joints)
            if (joint.spec.name == "LeftUpLeg") joint.spec.eulerOrder = EulerOrder::XYZ;
    });
    read = readThroughOsgDB(misfit);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("walker.actor:" + std::to_string(clipLine(misfit)) + ": clip 'walk': "),
              std::string::npos)
        << read.message();
    EXPECT_NE(read.message().find("does not fit the actor: joint 'LeftUpLeg' turns in ZYX order in the file and in "
                                  "XYZ order here"),
              std::string::npos)
        << read.message();
}

TEST(ActorFileClips, AnAmcClipReadAgainstItsAsfSkeletonAtAScalePlaysTheCapture)
{
    // An actor of 11.asf at this scale, without the ASF's limits (this capture goes past its rfingers' limits, which
    // would clamp them), and a clip naming the motion and its skeleton.
    constexpr double kScale = 0.05;
    AsfImportOptions asfOptions;
    asfOptions.scale = kScale;
    asfOptions.applyLimits = false;
    const AsfImport skeleton = readAsfFile(repositoryMocap("asfamc/11.asf"), asfOptions);
    ASSERT_TRUE(skeleton) << skeleton.error;
    ActorDocument document = makeDocument(*skeleton.definition);
    MotionFileOptions options;
    options.skeletonFile = "motion/11.asf";
    options.scale = kScale;
    document.clips.push_back(walkFromFile("motion/11_01.amc", options));
    const std::string path =
        writeActorBesideMotionFiles("clip_file_amc", document, {"asfamc/11.asf", "asfamc/11_01.amc"});

    osg::ref_ptr<ActorNode> actor;
    ClipPtr clip;
    readActorWithWalkClip(path, actor, clip);
    ASSERT_TRUE(clip);
    EXPECT_EQ(clip->getFrameRate(), 120.0);

    // Every bone where the independent reading of the files puts it, scaled. The root translates, so a root travel
    // left unscaled would be 20 times too far.
    expectToFollowAsfAmc(*actor, repositoryMocap("asfamc/11.asf"), repositoryMocap("asfamc/11_01.amc"), kScale);
}

TEST(ActorFileClips, ABvhClipFileTakesItsScaleAndDropsItsFirstFrameWhenTold)
{
    BvhImportOptions bvhOptions;
    bvhOptions.scale = 0.01;
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/12_03.bvh"), bvhOptions);
    ASSERT_TRUE(imported) << imported.error;
    ActorDocument document = makeDocument(*imported.definition);
    MotionFileOptions options;
    options.scale = 0.01;
    options.dropFirstFrame = true;
    document.clips.push_back(walkFromFile("motion/12_03.bvh", options));
    const std::string path = writeActorBesideMotionFiles("clip_file_scaled", document, {"bvh/12_03.bvh"});

    osg::ref_ptr<ActorNode> actor;
    ClipPtr clip;
    readActorWithWalkClip(path, actor, clip);
    ASSERT_TRUE(clip);
    ASSERT_EQ(clip->getNumFrames(), imported.clip->getNumFrames() - 1);

    // Frame 0 of the clip is the file's frame 1; the hips at update frame 5 (60 Hz) are at the file's frame 11.
    const reference::Bvh bvh = reference::readBvh(repositoryMocap("bvh/12_03.bvh"));
    const int hips = actor->getJointIndex(bvh.joints[0].name);
    ASSERT_GE(hips, 0);
    osg::ref_ptr<osg::Group> root = new osg::Group;
    root->addChild(actor.get());
    for (unsigned n : {0u, 5u})
    {
        runUpdate(*root, n);
        // The file's frame time (.008333) is not quite 1/120 s: update frame 5 falls a hair past file frame 11.
        const glm::dvec3 expected = reference::bvhPositions(bvh, 2 * n + 1)[0] * 0.01;
        EXPECT_LT((actor->getJointWorldPosition(static_cast<unsigned>(hips)) - zUp(expected)).length(), 1e-6)
            << "update frame " << n;
    }
}

TEST(ActorFileClips, AnAmcClipWhoseSkeletonIsMissingFailsTheReadAtItsLine)
{
    const AsfImport skeleton = readAsfFile(repositoryMocap("asfamc/11.asf"));
    ASSERT_TRUE(skeleton) << skeleton.error;
    ActorDocument document = makeDocument(*skeleton.definition);
    MotionFileOptions options;
    options.skeletonFile = "motion/12.asf";
    document.clips.push_back(walkFromFile("motion/11_01.amc", options));
    const std::string path =
        writeActorBesideMotionFiles("clip_file_amc_missing", document, {"asfamc/11.asf", "asfamc/11_01.amc"});
    osgDB::ReaderWriter::ReadResult read = readThroughOsgDB(path);
    EXPECT_FALSE(read.validNode());
    EXPECT_NE(read.message().find("walker.actor:"), std::string::npos) << read.message();
    EXPECT_NE(read.message().find(": clip 'walk': cannot find the skeleton file 'motion/12.asf'"), std::string::npos)
        << read.message();
}

TEST(ActorFileClips, ApplyingAnUnreadClipFileLeavesTheClipOutInsteadOfCrashing)
{
    // Only createActorNode() reads clip files; applyClips() gets such a clip from a hand-edited embedded document.
    const MocapImport imported = readBvhFile(repositoryMocap("bvh/12_03.bvh"));
    ASSERT_TRUE(imported) << imported.error;
    ActorDocument document;
    ClipDocument unread;
    unread.file = "walk.bvh";
    unread.fileOptions.name = "walk";
    unread.play = true;
    document.clips.push_back(unread);
    ClipDocument read;
    read.clip = imported.clip;
    document.clips.push_back(read);
    osg::ref_ptr<ActorNode> actor = new ActorNode(imported.definition);
    applyClips(*actor, document);
    ASSERT_TRUE(actor->getClipLibrary());
    EXPECT_FALSE(actor->getClipLibrary()->getClip("walk"));
    EXPECT_TRUE(actor->getClipLibrary()->getClip("12_03"));
    EXPECT_FALSE(actor->findController("walk"));
}
