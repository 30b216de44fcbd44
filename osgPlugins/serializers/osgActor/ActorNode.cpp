/* osgActor::ActorNode in OSG's serializer formats (.osgt, .osgb, .osgx).
 *
 * The skeleton nodes and attached geometry are ordinary children, written by osg::Group's wrapper before the
 * fields here. The definition is not an osg::Object: it is written as the joint part of a .actor file, one line
 * per string, and read with the .actor reader; reading it binds the skeleton nodes already read. */
#include <osgActor/ActorNode>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>

#include <charconv>
#include <sstream>

namespace {

// Text formats write doubles with the stream's precision (6 digits unless the "precision" option says otherwise),
// which would move a read-back actor. The actor's own numbers are therefore written as their shortest exact text
// in .osgt and .osgx, and as raw doubles in .osgb.
void writeExact(osgDB::OutputStream& os, double value)
{
    if (os.isBinary())
    {
        os << value;
        return;
    }
    char buffer[32];
    const std::to_chars_result written = std::to_chars(buffer, buffer + sizeof(buffer), value);
    os << std::string(buffer, written.ptr);
}

double readExact(osgDB::InputStream& is)
{
    double value = 0.0;
    if (is.isBinary())
    {
        is >> value;
        return value;
    }
    std::string text;
    is >> text;
    std::from_chars(text.data(), text.data() + text.size(), value);
    return value;
}

void writeExact(osgDB::OutputStream& os, const osg::Vec3d& v)
{
    for (int i = 0; i < 3; ++i) writeExact(os, v[i]);
    os << std::endl;
}

osg::Vec3d readExactVec3d(osgDB::InputStream& is)
{
    osg::Vec3d v;
    for (int i = 0; i < 3; ++i) v[i] = readExact(is);
    return v;
}

void writeExact(osgDB::OutputStream& os, const osg::Quat& q)
{
    for (int i = 0; i < 4; ++i) writeExact(os, q[i]);
    os << std::endl;
}

osg::Quat readExactQuat(osgDB::InputStream& is)
{
    osg::Quat q;
    for (int i = 0; i < 4; ++i) q[i] = readExact(is);
    return q;
}

/** The definition and the actor's IK chains, as the lines of a .actor file. */
std::vector<std::string> definitionLines(const osgActor::ActorNode& actor)
{
    osgActor::ActorDocument document = osgActor::makeDocument(*actor.getDefinition());
    for (const osgActor::IkChainPtr& chain : actor.getIkChains())
        document.ikChains.push_back(osgActor::IkChainDocument{chain->getSpec(), 0});
    std::ostringstream text;
    osgActor::writeActor(text, document);
    std::vector<std::string> lines;
    std::istringstream in(text.str());
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
}

} // namespace

static bool checkDefinition(const osgActor::ActorNode& actor) { return actor.getDefinition() != nullptr; }

static bool readDefinition(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    const unsigned int count = is.readSize();
    is >> is.BEGIN_BRACKET;
    std::string text;
    for (unsigned int i = 0; i < count; ++i)
    {
        std::string line;
        is.readWrappedString(line);
        text += line + "\n";
    }
    is >> is.END_BRACKET;
    std::istringstream in(text);
    const osgActor::ActorReadResult read = osgActor::readActor(in, "definition of actor '" + actor.getName() + "'");
    // A broken definition or skeleton fails the whole read (the ReadResult carries the message): no half-built actor.
    if (!read)
    {
        is.throwException("osgActor: " + read.error);
        return false;
    }
    if (!actor.setDefinition(read.definition, osgActor::ActorNode::BIND_EXISTING_SKELETON_NODES))
    {
        is.throwException("osgActor: the skeleton nodes of actor '" + actor.getName() +
                          "' do not match its definition");
        return false;
    }
    for (const osgActor::IkChainPtr& chain : read.ikChains) actor.addIkChain(chain);
    return true;
}

static bool writeDefinition(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    const std::vector<std::string> lines = definitionLines(actor);
    os.writeSize(static_cast<unsigned int>(lines.size()));
    os << os.BEGIN_BRACKET << std::endl;
    for (const std::string& line : lines)
    {
        os.writeWrappedString(line);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}

// The DOF vector (l_conf): radians and model units, in the definition's order.
static bool checkDofs(const osgActor::ActorNode& actor) { return actor.getNumDofs() > 0; }

static bool readDofs(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    const unsigned int count = is.readSize();
    is >> is.BEGIN_BRACKET;
    std::vector<double> values(count);
    for (double& value : values) value = readExact(is);
    is >> is.END_BRACKET;
    if (is.getException()) return false; // the definition failed already; keep its message
    if (actor.setDofs(values)) return true;
    is.throwException("osgActor: actor '" + actor.getName() + "' has " + std::to_string(count) +
                      " DOF values for " + std::to_string(actor.getNumDofs()) + " DOFs, or one is not finite");
    return false;
}

static bool writeDofs(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    os.writeSize(actor.getNumDofs());
    os << os.BEGIN_BRACKET << std::endl;
    for (const double value : actor.getDofs())
    {
        writeExact(os, value);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}

// Pre- and post-transforms (model units, unit quaternions), always written.
static bool checkPreTranslation(const osgActor::ActorNode&) { return true; }
static bool readPreTranslation(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    actor.setPreTranslation(readExactVec3d(is));
    return true;
}
static bool writePreTranslation(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    writeExact(os, actor.getPreTranslation());
    return true;
}

static bool checkPreRotation(const osgActor::ActorNode&) { return true; }
static bool readPreRotation(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    actor.setPreRotation(readExactQuat(is));
    return true;
}
static bool writePreRotation(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    writeExact(os, actor.getPreRotation());
    return true;
}

static bool checkPostTranslation(const osgActor::ActorNode&) { return true; }
static bool readPostTranslation(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    actor.setPostTranslation(readExactVec3d(is));
    return true;
}
static bool writePostTranslation(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    writeExact(os, actor.getPostTranslation());
    return true;
}

static bool checkPostRotation(const osgActor::ActorNode&) { return true; }
static bool readPostRotation(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    actor.setPostRotation(readExactQuat(is));
    return true;
}
static bool writePostRotation(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    writeExact(os, actor.getPostRotation());
    return true;
}

// The block flag. An actor is posed before it is blocked, so a blocked actor read back shows its frozen pose.
static bool checkBlocked(const osgActor::ActorNode& actor) { return actor.getBlocked(); }

static bool readBlocked(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    bool blocked = false;
    is >> blocked;
    if (blocked) actor.update(nullptr);
    actor.setBlocked(blocked);
    return true;
}

static bool writeBlocked(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    os << actor.getBlocked() << std::endl;
    return true;
}

REGISTER_OBJECT_WRAPPER(osgActor_ActorNode, new osgActor::ActorNode, osgActor::ActorNode,
                        "osg::Object osg::Node osg::Group osg::Transform osg::MatrixTransform osgActor::ActorNode")
{
    ADD_USER_SERIALIZER(Definition); // first: the fields below need it
    ADD_USER_SERIALIZER(Dofs);
    ADD_USER_SERIALIZER(PreTranslation);
    ADD_USER_SERIALIZER(PreRotation);
    ADD_USER_SERIALIZER(PostTranslation);
    ADD_USER_SERIALIZER(PostRotation);
    ADD_USER_SERIALIZER(Blocked); // last: it poses the actor before freezing it
}
