/* Bad .actor files read through osgDB's plugin lookup: each gives a ReadResult error naming the file and the line,
 * and no node. */
#include "PluginTestUtil"

#include <osgDB/WriteFile>

using namespace osgActor::test;

namespace {

/** Writes text to a file, reads it through the registry, and returns the ReadResult's message. */
std::string readError(const std::string& name, const std::string& text)
{
    const std::string path = writeTextFile(name, text);
    osgDB::ReaderWriter::ReadResult result = osgDB::Registry::instance()->readNode(path, nullptr);
    EXPECT_FALSE(result.validNode()) << name;
    EXPECT_EQ(result.status(), osgDB::ReaderWriter::ReadResult::ERROR_IN_READING_FILE) << name;
    EXPECT_FALSE(osgDB::readRefNodeFile(path).valid()) << "readNodeFile gives no half-built actor for " << name;
    const std::string message = result.message();
    EXPECT_EQ(message.rfind(path + ":", 0), 0u) << "the message names the file: " << message;
    return message.substr(std::min(message.size(), path.size() + 1)); // "line: text"
}

const std::string kHeader = "osgactor 1\nactor a {\n";

} // namespace

TEST(ActorPluginErrors, TruncatedFile)
{
    EXPECT_EQ(readError("truncated.actor", kHeader + " joint b {\n  dof rx min -10 max"),
              "4: the file ends inside the block opened at line 3");
}

TEST(ActorPluginErrors, UnknownKeyword)
{
    EXPECT_EQ(readError("keyword.actor", kHeader + " joint b {\n  dof rx\n  wobble 3\n }\n}\n"),
              "5: unknown keyword 'wobble' in a joint");
}

TEST(ActorPluginErrors, DuplicateJoint)
{
    EXPECT_EQ(readError("duplicate.actor", kHeader + " joint b {\n  joint c\n  joint c\n }\n}\n"),
              "5: actor 'a': joint name 'c' is used twice");
}

TEST(ActorPluginErrors, UnknownParentJoint)
{
    EXPECT_EQ(readError("unknown.actor", kHeader + " joint b\n joint c {\n  parent nobody\n }\n}\n"),
              "4: actor 'a': joint 'c' names an unknown parent 'nobody'");
}

TEST(ActorPluginErrors, Cycle)
{
    const std::string message =
        readError("cycle.actor", kHeader + " joint b { parent c }\n joint c { parent b }\n joint r\n}\n");
    EXPECT_EQ(message, "3: actor 'a': the joints form a parent cycle: 'b' -> 'c' -> 'b'");
}

TEST(ActorPluginErrors, BadNumber)
{
    EXPECT_EQ(readError("number.actor", kHeader + " joint b {\n  offset 0 0.5.1 0\n }\n}\n"),
              "4: '0.5.1' is not a number");
}

TEST(ActorPluginErrors, NaN)
{
    EXPECT_EQ(readError("nan.actor", kHeader + " joint b {\n  dof rz default NaN\n }\n}\n"),
              "4: 'NaN' is not a finite number");
}

TEST(ActorPluginErrors, MissingModelFile)
{
    EXPECT_EQ(readError("missing_model.actor", kHeader + " joint b {\n  shape sphere { radius 1 }\n"
                                                         "  model \"no_such_model.osgt\"\n }\n}\n"),
              "5: cannot find the model file 'no_such_model.osgt'");
}

TEST(ActorPluginErrors, UnreadableModelFile)
{
    writeTextFile("garbage.osgt", "this is not an osgt file\n");
    const std::string message = readError("garbage_model.actor", kHeader + " joint b {\n  model garbage.osgt\n }\n}\n");
    EXPECT_EQ(message.rfind("4: cannot read the model file '", 0), 0u) << message;
}
