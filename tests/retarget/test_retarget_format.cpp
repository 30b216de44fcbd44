// Retargeting in .actor files: "jointmap" sections and map files (errors with file and line first), a clip's
// "retarget" statement read and written back, the clip retargeted when the actor is made, and the OSG-layer call.
#include "RetargetTestUtil"

#include <osgActor/ActorRetarget>
#include <osgActor/ActorSceneIO>
#include <osgActor/core/retarget/BuiltInJointMaps>
#include <osgActor/core/retarget/HAnimHumanoid>
#include <osgActor/io/ActorWriter>
#include <osgActor/io/JointMapSection>

#include <fstream>
#include <sstream>

using namespace osgActor;
using namespace osgActor::test;

namespace {

/** data/humanoid.actor's text with extra statements inserted before the closing brace of its actor block. */
std::string humanoidWith(const std::string& extra)
{
    std::ifstream in(std::string(OSGACTOR_TEST_DATA_DIR) + "/humanoid.actor");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::size_t end = text.rfind('}');
    return text.substr(0, end) + extra + "\n}\n";
}

/** The line number (1-based) at which a piece of text starts in a whole. */
int lineOf(const std::string& whole, const std::string& piece)
{
    const std::size_t at = whole.find(piece);
    EXPECT_NE(at, std::string::npos) << piece;
    return 1 + static_cast<int>(std::count(whole.begin(), whole.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

ActorReadResult readText(const std::string& text, const std::string& name = "h.actor")
{
    std::istringstream in(text);
    return readActor(in, name);
}

std::string readError(const std::string& text)
{
    const ActorReadResult result = readText(text);
    EXPECT_FALSE(result);
    EXPECT_EQ(result.definition, nullptr) << "nothing half-built";
    return result.error;
}

/** The document a text reads into, written out and read back. */
ActorReadResult writtenAndReadBack(const std::string& text)
{
    const ActorReadResult first = readText(text);
    EXPECT_TRUE(first) << first.error;
    std::ostringstream written;
    writeActor(written, first.document);
    return readText(written.str());
}

/** A file in the test's build folder. */
std::string writeFile(const std::string& name, const std::string& text)
{
    const std::string path = std::string(OSGACTOR_TEST_BINARY_DIR) + "/" + name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

} // namespace

TEST(JointMapSection, RefusesBadStatementsWithTheirLines)
{
    const std::string badKeyword = humanoidWith("    jointmap {\n        maps HumanoidRoot HumanoidRoot\n    }");
    EXPECT_EQ(readError(badKeyword), "h.actor:" + std::to_string(lineOf(badKeyword, "maps ")) +
                                         ": unknown keyword 'maps' in a joint map (base, map)");
    const std::string badBase = humanoidWith("    jointmap { map a b; base mixamo }");
    EXPECT_EQ(readError(badBase), "h.actor:" + std::to_string(lineOf(badBase, "jointmap {")) +
                                      ": 'base' must come first in a joint map");
    const std::string twice = humanoidWith("    jointmap { map l_hip l_hip }\n    jointmap { map r_hip r_hip }");
    EXPECT_EQ(readError(twice), "h.actor:" + std::to_string(lineOf(twice, "jointmap { map r_hip")) +
                                    ": the actor's joint map is given twice");
}

TEST(JointMapSection, RefusesTheActorsMapNamingAJointItLacksOrGoingRoundInACycle)
{
    const std::string missing = humanoidWith("    jointmap {\n        map HumanoidRoot HumanoidRoot\n"
                                             "        map pelvis sacroiliac\n    }");
    EXPECT_EQ(readError(missing), "h.actor:" + std::to_string(lineOf(missing, "map pelvis")) +
                                      ": joint map names joint 'pelvis', which the skeleton 'humanoid' does not have");
    const std::string cycle = humanoidWith("    jointmap {\n        map l_hip thigh\n        map thigh leg\n"
                                           "        map leg thigh\n    }");
    EXPECT_EQ(readError(cycle), "h.actor:" + std::to_string(lineOf(cycle, "map l_hip")) +
                                    ": joint map has a cycle: l_hip -> thigh -> leg -> thigh");
}

TEST(JointMapSection, KeepsTheSectionsThroughAReadAndAWrite)
{
    const std::string text = humanoidWith("    jointmap { map HumanoidRoot HumanoidRoot; map l_hip l_hip }\n"
                                          "    jointmap studio { base cmu_bvh; map \"Left Thigh\" l_hip }");
    const ActorReadResult second = writtenAndReadBack(text);
    ASSERT_TRUE(second) << second.error;
    ActorJointMaps maps;
    std::string error;
    ASSERT_TRUE(readActorJointMaps(second.document.sections, "h.actor", maps, error)) << error;
    ASSERT_TRUE(maps.hasOwn);
    EXPECT_EQ(maps.own.getEntries().size(), 2u);
    ASSERT_EQ(maps.named.count("studio"), 1u);
    const JointMap& studio = maps.named.at("studio");
    EXPECT_TRUE(studio.getLooseMatching());
    ASSERT_NE(studio.find("left thigh"), nullptr);
    EXPECT_EQ(studio.find("left thigh")->hanim, "l_hip");
    ASSERT_NE(studio.find("LeftForeArm"), nullptr); // from its base
}

TEST(JointMapSection, ReadsMapFilesAndSaysWhereTheyAreWrong)
{
    JointMap map;
    std::string error;
    const std::string good = writeFile("good.map", "# Boxing_Toes.bvh's names\nbase motionbuilder_bvh\nmap Ab vl3\n");
    ASSERT_TRUE(readJointMapFile(good, map, error)) << error;
    EXPECT_EQ(map.find("Ab")->hanim, "vl3");
    EXPECT_EQ(map.find("Ab")->origin, good + ":3");
    const std::string bad = writeFile("bad.map", "map Hips\n");
    EXPECT_FALSE(readJointMapFile(bad, map, error));
    EXPECT_EQ(error, bad + ":1: 'map' takes a joint and its H-Anim joint, not 1 value");
    EXPECT_FALSE(readJointMapFile(std::string(OSGACTOR_TEST_BINARY_DIR) + "/none.map", map, error));
    EXPECT_NE(error.find("cannot open the joint map file"), std::string::npos);
}

TEST(ClipRetargetStatement, IsOnlyForClipsFromFilesAndWritesBack)
{
    const std::string keyed = humanoidWith("    clip bow {\n        retarget auto\n        channel vl5.rx { key 0 0; "
                                           "key 1 30 }\n    }");
    EXPECT_EQ(readError(keyed), "h.actor:" + std::to_string(lineOf(keyed, "retarget auto")) +
                                    ": 'retarget' is for a clip whose motion is in a file");
    const std::string badIk = humanoidWith("    clip walk { file \"w.bvh\"; retarget auto { ik maybe } }");
    EXPECT_EQ(readError(badIk), "h.actor:" + std::to_string(lineOf(badIk, "clip walk")) + ": 'ik' takes on or off");
    const std::string text = humanoidWith("    clip walk { file \"w.bvh\"; retarget studio { ik off } }\n"
                                          "    clip dance { file \"d.amc\" { skeleton \"d.asf\" }; retarget auto }");
    const ActorReadResult second = writtenAndReadBack(text);
    ASSERT_TRUE(second) << second.error;
    ASSERT_EQ(second.document.clips.size(), 3u); // and "wave"
    for (const ClipDocument& clip : second.document.clips)
    {
        if (clip.name() == "walk")
        {
            EXPECT_TRUE(clip.retarget.enabled);
            EXPECT_EQ(clip.retarget.sourceMap, "studio");
            EXPECT_FALSE(clip.retarget.ik);
        }
        if (clip.name() == "dance")
        {
            EXPECT_TRUE(clip.retarget.enabled);
            EXPECT_TRUE(clip.retarget.sourceMap.empty());
            EXPECT_TRUE(clip.retarget.ik);
        }
    }
}

TEST(ClipRetargetStatement, RetargetsTheCharlestonOntoTheHumanoidWhenTheActorIsMade)
{
    // The issue's own example: CMU's Charleston (ASF/AMC), retargeted at load onto the H-Anim humanoid.
    const std::string motion = "file \"" + repositoryMocap("asfamc/charleston1.amc") + "\" { skeleton \"" +
                               repositoryMocap("asfamc/charleston.asf") + "\" }";
    const std::string text =
        humanoidWith("    clip dance {\n        play loop\n        " + motion + "\n        retarget auto\n    }");
    const ActorReadResult read = readText(text);
    ASSERT_TRUE(read) << read.error;
    const ActorNodeResult made = createActorNode(read.document, read.definition, "h.actor", nullptr);
    ASSERT_TRUE(made.actor) << made.error;
    const ClipPtr dance = made.actor->getClipLibrary()->getClip("dance");
    ASSERT_TRUE(dance);
    EXPECT_TRUE(dance->isUniform());
    EXPECT_EQ(dance->getNumFrames(), 506u);
    EXPECT_EQ(dance->getNumChannels(), read.definition->getNumDofs());
    EXPECT_GE(dance->findChannel("l_knee.rx"), 0);
    // The dancer's knees bend: the humanoid's do too, within their limits.
    double largestBend = 0.0;
    const unsigned knee = static_cast<unsigned>(dance->findChannel("l_knee.rx"));
    for (unsigned f = 0; f < dance->getNumFrames(); ++f) largestBend = std::max(largestBend, dance->getFrame(f)[knee]);
    EXPECT_GT(largestBend, degrees(30));
    EXPECT_LE(largestBend, degrees(150));

    // A source map the file does not have is an error at the clip's retarget line.
    const std::string unknownMap =
        humanoidWith("    clip dance {\n        " + motion + "\n        retarget studio\n    }");
    const ActorReadResult unknown = readText(unknownMap);
    ASSERT_TRUE(unknown) << unknown.error;
    const ActorNodeResult failed = createActorNode(unknown.document, unknown.definition, "h.actor", nullptr);
    EXPECT_FALSE(failed.actor);
    EXPECT_EQ(failed.error, "h.actor:" + std::to_string(lineOf(unknownMap, "retarget studio")) +
                                ": clip 'dance': retargeting: no jointmap section named 'studio'");
}

TEST(ActorRetarget, AddsARetargetedClipToAnActorWithItsOwnMap)
{
    // An actor whose joint names no built-in map knows, with a jointmap section: the map goes with the actor.
    const std::string text = humanoidWith("    jointmap { base hanim }");
    const ActorReadResult read = readText(text);
    ASSERT_TRUE(read) << read.error;
    const ActorNodeResult made = createActorNode(read.document, read.definition, "h.actor", nullptr);
    ASSERT_TRUE(made.actor) << made.error;
    EXPECT_EQ(getActorJointMap(*made.actor).getEntries().size(),
              builtInJointMap(JointMapStyle::HAnim).getEntries().size());

    const MocapImport walk = readBvhScaled(repositoryMocap("bvh/12_03.bvh"));
    RetargetSkeleton source = skeleton(walk.definition);
    RetargetClipOptions options;
    options.name = "walk";
    options.ik = true;
    const RetargetClipResult result = retargetClipOntoActor(*made.actor, source, *walk.clip, options);
    ASSERT_TRUE(result) << result.error;
    EXPECT_EQ(made.actor->getClipLibrary()->getClip("walk"), result.clip);
    EXPECT_FALSE(result.feet.empty());

    // Nothing is added when the source cannot be retargeted.
    ActorDefinitionBuilder b("crane");
    b.addJoint("base").dofs(kRotationDofs);
    RetargetSkeleton crane = skeleton(b.build().definition);
    const RetargetClipResult refused = retargetClipOntoActor(*made.actor, crane, *walk.clip, options);
    EXPECT_FALSE(refused);
    EXPECT_NE(refused.error.find("retargeting clip '12_03' onto actor 'humanoid'"), std::string::npos) << refused.error;
}
