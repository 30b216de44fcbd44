/* osgActor::ActorNode in OSG's serializer formats (.osgt, .osgb, .osgx).
 *
 * The skeleton nodes and attached geometry are ordinary children, written by osg::Group's wrapper before the
 * fields here. The definition and the clip library are written as osg::Objects (ActorDefinitionObject,
 * ClipLibraryObject, the same for every actor that shares them), so that osgDB writes each once and reads it back
 * as one object; the actor's own motion (players, trajectories, IK chains) as .actor text (ActorPartsText). Reading
 * the definition binds the skeleton nodes already read.
 *
 * The Definition field, in both of its forms:
 *   Definition 0 { <ActorDefinitionObject> <ClipLibraryObject or NULL> Motion <n> { <n lines> } }   written now
 *   Definition <n> { <n lines of one whole .actor text> }                                         still read
 * An old file's count is never 0 (its text has a header), which tells the two apart in the binary format too. */
#include "SerializedLines"
#include "SerializedNumbers"

#include <osgActor/ActorNode>
#include <osgActor/ActorPartsText>
#include <osgActor/StreamNumbers>

#include <osgDB/InputStream>
#include <osgDB/ObjectWrapper>
#include <osgDB/OutputStream>

namespace {

// Every number of the actor's own fields is written exactly (osgActor/StreamNumbers); a word that is not a finite
// number fails the read with its message.
void writeExact(osgDB::OutputStream& os, const osg::Vec3d& v)
{
    for (int i = 0; i < 3; ++i) osgActor::writeStreamNumber(os, v[i]);
    os << std::endl;
}

bool readExact(osgDB::InputStream& is, osg::Vec3d& v, const std::string& what)
{
    for (int i = 0; i < 3; ++i)
        if (!osgActor::readStreamNumber(is, v[i], what)) return false;
    return true;
}

void writeExact(osgDB::OutputStream& os, const osg::Quat& q)
{
    for (int i = 0; i < 4; ++i) osgActor::writeStreamNumber(os, q[i]);
    os << std::endl;
}

bool readExact(osgDB::InputStream& is, osg::Quat& q, const std::string& what)
{
    for (int i = 0; i < 4; ++i)
        if (!osgActor::readStreamNumber(is, q[i], what)) return false;
    return true;
}

/** What messages call an actor's texts ("definition of actor 'a'", "motion of actor 'a'"). */
std::string textName(const char* what, const osgActor::ActorNode& actor)
{
    return std::string(what) + " of actor '" + actor.getName() + "'";
}

} // namespace

using namespace osgActorSerializers;

static bool checkDefinition(const osgActor::ActorNode& actor) { return actor.getDefinition() != nullptr; }

static bool readDefinition(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    std::string error;
    const unsigned int wholeTextLines = is.readSize();
    if (wholeTextLines > 0)
    {
        const std::vector<std::string> lines = readLinesAfterCount(is, wholeTextLines);
        if (is.getException()) return false;
        if (osgActor::readWholeActorLines(actor, lines, textName("definition", actor), error)) return true;
        return failRead(is, error);
    }
    is >> is.BEGIN_BRACKET;
    const osg::ref_ptr<osgActor::ActorDefinitionObject> definition =
        is.readObjectOfType<osgActor::ActorDefinitionObject>();
    const osg::ref_ptr<osgActor::ClipLibraryObject> library = is.readObjectOfType<osgActor::ClipLibraryObject>();
    is >> is.PROPERTY("Motion");
    const std::vector<std::string> motion = readLines(is);
    is >> is.END_BRACKET;
    if (is.getException()) return false;
    if (!definition || !definition->getDefinition())
        return failRead(is, "actor '" + actor.getName() + "' has no definition");
    if (!actor.setDefinition(definition->getDefinition(), osgActor::ActorNode::BIND_EXISTING_SKELETON_NODES))
        return failRead(is, "the skeleton nodes of actor '" + actor.getName() + "' do not match its definition");
    if (library) actor.setClipLibrary(library->getLibrary());
    if (osgActor::readMotionLines(actor, motion, textName("motion", actor), error)) return true;
    return failRead(is, error);
}

static bool writeDefinition(osgDB::OutputStream& os, const osgActor::ActorNode& actor)
{
    os.writeSize(0u); // no whole .actor text: the shared objects follow
    os << os.BEGIN_BRACKET << std::endl;
    os.writeObject(actor.getDefinitionObject());
    os.writeObject(actor.getClipLibraryObject());
    os << os.PROPERTY("Motion");
    writeLines(os, osgActor::writeMotionLines(actor));
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
    for (double& value : values)
        if (!osgActor::readStreamNumber(is, value, textName("DOF values", actor))) return false;
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
        osgActor::writeStreamNumber(os, value);
        os << std::endl;
    }
    os << os.END_BRACKET << std::endl;
    return true;
}

// Pre- and post-transforms (model units, unit quaternions), always written, exactly; one the actor refuses (not
// finite, beyond kMaxDofMagnitude, a zero rotation) fails the read. One macro makes the check, read and write
// functions ADD_USER_SERIALIZER(NAME) expects for a field with setNAME/getNAME.
#define OSGACTOR_EXACT_TRANSFORM_FIELD(NAME, TYPE)                                                                 \
    static bool check##NAME(const osgActor::ActorNode&) { return true; }                                          \
    static bool read##NAME(osgDB::InputStream& is, osgActor::ActorNode& actor)                                    \
    {                                                                                                              \
        TYPE value;                                                                                                \
        if (!readExact(is, value, textName(#NAME, actor))) return false;                                           \
        actor.set##NAME(value);                                                                                    \
        if (actor.get##NAME() == value) return true;                                                               \
        return failRead(is, textName(#NAME, actor) + " is not one an actor holds");                                \
    }                                                                                                              \
    static bool write##NAME(osgDB::OutputStream& os, const osgActor::ActorNode& actor)                            \
    {                                                                                                              \
        writeExact(os, actor.get##NAME());                                                                         \
        return true;                                                                                               \
    }

OSGACTOR_EXACT_TRANSFORM_FIELD(PreTranslation, osg::Vec3d)
OSGACTOR_EXACT_TRANSFORM_FIELD(PreRotation, osg::Quat)
OSGACTOR_EXACT_TRANSFORM_FIELD(PostTranslation, osg::Vec3d)
OSGACTOR_EXACT_TRANSFORM_FIELD(PostRotation, osg::Quat)

// The block flag. An actor is posed before it is blocked, so a blocked actor read back shows its frozen pose.
static bool checkBlocked(const osgActor::ActorNode& actor) { return actor.getBlocked(); }

static bool readBlocked(osgDB::InputStream& is, osgActor::ActorNode& actor)
{
    bool blocked = false;
    is >> blocked;
    if (blocked)
    {
        actor.updatePose();      // the matrices queries answer with
        actor.update(nullptr);   // the scene graph
    }
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
    BEGIN_ENUM_SERIALIZER(BoundMode, BOUND_COVERS_ROTATIONS);
        ADD_ENUM_VALUE(BOUND_FOLLOWS_POSE);
        ADD_ENUM_VALUE(BOUND_COVERS_ROTATIONS);
    END_ENUM_SERIALIZER();
    ADD_USER_SERIALIZER(Blocked); // last: it poses the actor before freezing it
}
