/* osgActor::ActorNode in the .osg format. Its fields follow osg::Group's children (the associates list puts
 * Group first), so reading the definition binds the skeleton nodes already read. The definition and clips are
 * written as a .actor file holding the joints and clips, one quoted string per line. */
#include "DotOsgNumbers"

#include <osgActor/ActorNode>
#include <osgActor/ActorSceneIO>
#include <osgActor/io/ActorReader>
#include <osgActor/io/ActorWriter>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

#include <sstream>

using osgActorDotOsg::exact;
using osgActorDotOsg::readExact;

namespace {

bool readActorNode(osg::Object& object, osgDB::Input& fr);
bool writeActorNode(const osg::Object& object, osgDB::Output& fw);

/** Reads the lines of a "Keyword n { ... }" block of quoted strings or numbers, one token each. */
std::vector<std::string> readBlockTokens(osgDB::Input& fr)
{
    std::vector<std::string> tokens;
    const int entry = fr[0].getNoNestedBrackets();
    fr += 3; // Keyword n {
    while (!fr.eof() && fr[0].getNoNestedBrackets() > entry)
    {
        tokens.push_back(fr[0].getStr());
        ++fr;
    }
    ++fr; // }
    return tokens;
}

bool readVec3d(osgDB::Input& fr, const char* keyword, osg::Vec3d& value)
{
    if (!fr[0].matchWord(keyword) || !readExact(fr[1].getStr(), value.x()) || !readExact(fr[2].getStr(), value.y()) ||
        !readExact(fr[3].getStr(), value.z()))
        return false;
    fr += 4;
    return true;
}

bool readQuat(osgDB::Input& fr, const char* keyword, osg::Quat& value)
{
    double v[4];
    if (!fr[0].matchWord(keyword))
        return false;
    for (int i = 0; i < 4; ++i)
        if (!readExact(fr[i + 1].getStr(), v[i])) return false;
    value.set(v[0], v[1], v[2], v[3]);
    fr += 5;
    return true;
}

bool readActorNode(osg::Object& object, osgDB::Input& fr)
{
    osgActor::ActorNode& actor = static_cast<osgActor::ActorNode&>(object);
    bool advanced = false;
    if (fr.matchSequence("Definition %i {"))
    {
        std::string text;
        for (const std::string& line : readBlockTokens(fr)) text += line + "\n";
        std::istringstream in(text);
        const osgActor::ActorReadResult read = osgActor::readActor(in, "definition of actor '" + actor.getName() + "'");
        if (read && actor.setDefinition(read.definition, osgActor::ActorNode::BIND_EXISTING_SKELETON_NODES))
        {
            osgActor::applyDefinitionDocument(actor, read.document, read.ikChains);
        }
        else if (!read)
            OSG_WARN << "osgActor: " << read.error << std::endl;
        advanced = true;
    }
    if (fr.matchSequence("Dofs %i {"))
    {
        std::vector<double> values;
        bool valid = true;
        for (const std::string& token : readBlockTokens(fr))
        {
            values.emplace_back();
            valid = readExact(token.c_str(), values.back()) && valid;
        }
        if (valid) actor.setDofs(values);
        else OSG_WARN << "osgActor: actor '" << actor.getName() << "' has a DOF value that is not a number"
                      << std::endl;
        advanced = true;
    }
    osg::Vec3d translation;
    osg::Quat rotation;
    if (readVec3d(fr, "PreTranslation", translation)) { actor.setPreTranslation(translation); advanced = true; }
    if (readQuat(fr, "PreRotation", rotation)) { actor.setPreRotation(rotation); advanced = true; }
    if (readVec3d(fr, "PostTranslation", translation)) { actor.setPostTranslation(translation); advanced = true; }
    if (readQuat(fr, "PostRotation", rotation)) { actor.setPostRotation(rotation); advanced = true; }
    if (fr[0].matchWord("BoundMode"))
    {
        if (fr[1].matchWord("COVERS_ROTATIONS")) actor.setBoundMode(osgActor::ActorNode::BOUND_COVERS_ROTATIONS);
        else if (fr[1].matchWord("FOLLOWS_POSE")) actor.setBoundMode(osgActor::ActorNode::BOUND_FOLLOWS_POSE);
        else
            OSG_WARN << "osgActor: actor '" << actor.getName() << "' has an unknown BoundMode '"
                     << (fr[1].getStr() ? fr[1].getStr() : "") << "' (FOLLOWS_POSE kept)" << std::endl;
        fr += 2;
        advanced = true;
    }
    if (fr[0].matchWord("Blocked"))
    {
        // Posed before it is frozen, so a blocked actor read back shows its pose.
        const bool blocked = fr[1].matchWord("TRUE");
        if (blocked)
        {
            actor.updatePose();    // the matrices queries answer with
            actor.update(nullptr); // the scene graph
        }
        actor.setBlocked(blocked);
        fr += 2;
        advanced = true;
    }
    return advanced;
}

bool writeActorNode(const osg::Object& object, osgDB::Output& fw)
{
    const osgActor::ActorNode& actor = static_cast<const osgActor::ActorNode&>(object);
    if (actor.getDefinition())
    {
        std::ostringstream text;
        osgActor::writeActor(text, osgActor::makeDefinitionDocument(actor));
        std::vector<std::string> lines;
        std::istringstream in(text.str());
        for (std::string line; std::getline(in, line);) lines.push_back(line);
        fw.indent() << "Definition " << lines.size() << " {" << std::endl;
        fw.moveIn();
        for (const std::string& line : lines) fw.indent() << fw.wrapString(line) << std::endl;
        fw.moveOut();
        fw.indent() << "}" << std::endl;

        fw.indent() << "Dofs " << actor.getNumDofs() << " {" << std::endl;
        fw.moveIn();
        for (const double value : actor.getDofs()) fw.indent() << exact(value) << std::endl;
        fw.moveOut();
        fw.indent() << "}" << std::endl;
    }
    const osg::Vec3d& pre = actor.getPreTranslation();
    const osg::Vec3d& post = actor.getPostTranslation();
    const osg::Quat& preRotation = actor.getPreRotation();
    const osg::Quat& postRotation = actor.getPostRotation();
    fw.indent() << "PreTranslation " << exact(pre.x()) << " " << exact(pre.y()) << " " << exact(pre.z()) << std::endl;
    fw.indent() << "PreRotation " << exact(preRotation.x()) << " " << exact(preRotation.y()) << " "
                << exact(preRotation.z()) << " " << exact(preRotation.w()) << std::endl;
    fw.indent() << "PostTranslation " << exact(post.x()) << " " << exact(post.y()) << " " << exact(post.z())
                << std::endl;
    fw.indent() << "PostRotation " << exact(postRotation.x()) << " " << exact(postRotation.y()) << " "
                << exact(postRotation.z()) << " " << exact(postRotation.w()) << std::endl;
    fw.indent() << "BoundMode "
                << (actor.getBoundMode() == osgActor::ActorNode::BOUND_COVERS_ROTATIONS ? "COVERS_ROTATIONS"
                                                                                     : "FOLLOWS_POSE")
                << std::endl;
    fw.indent() << "Blocked " << (actor.getBlocked() ? "TRUE" : "FALSE") << std::endl;
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ActorNode)
(new osgActor::ActorNode, "osgActor::ActorNode", "Object Node Transform MatrixTransform Group osgActor::ActorNode",
 &readActorNode, &writeActorNode, osgDB::DotOsgWrapper::READ_AND_WRITE);
