/* osgActor::ActorNode in the .osg format. Its fields follow osg::Group's children (the associates list puts
 * Group first), so reading the definition binds the skeleton nodes already read. The definition and the clip
 * library are written as shared objects (ActorDefinitionObject, ClipLibraryObject), which osgDB writes once and
 * then as "Use <id>"; the actor's own motion (players, trajectories, IK chains) as .actor text, one quoted string
 * per line (ActorPartsText). Files that hold a whole .actor text per actor ("Definition <n> { ... }", the form
 * written before) are still read. */
#include "DotOsgBlocks"

#include <osgActor/ActorNode>
#include <osgActor/ActorPartsText>
#include <osgActor/text/Numbers>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

#include <algorithm>

using namespace osgActorDotOsg;

namespace {

bool readActorNode(osg::Object& object, osgDB::Input& fr);
bool writeActorNode(const osg::Object& object, osgDB::Output& fw);

/** Reads the field "keyword v1 .. vCount" when it is next: true, and fr passes over it. valid says whether every
  * value is a finite number (read exactly, osgActor/text/Numbers); values are set only then, and a warning names
  * the word that is not. */
bool readNumbersField(osgDB::Input& fr, const char* keyword, double* values, int count,
                      const osgActor::ActorNode& actor, bool& valid)
{
    if (!fr[0].matchWord(keyword)) return false;
    double read[4];
    valid = true;
    for (int i = 0; i < count && valid; ++i)
    {
        const char* word = fr[i + 1].getStr();
        valid = word && osgActor::parseNumber(word, read[i]);
        if (!valid)
            OSG_WARN << "osgActor: actor '" << actor.getName() << "' " << keyword << ": "
                     << osgActor::numberProblem(word ? word : "") << " (field ignored)" << std::endl;
    }
    if (valid) std::copy(read, read + count, values);
    fr += count + 1;
    return true;
}

/** Writes the field "keyword v1 .. vCount", each value exactly (readNumbersField reads it back equal). */
void writeNumbersField(osgDB::Output& fw, const char* keyword, const double* values, int count)
{
    fw.indent() << keyword;
    for (int i = 0; i < count; ++i) fw << ' ' << osgActor::formatNumber(values[i]);
    fw << std::endl;
}

bool readActorNode(osg::Object& object, osgDB::Input& fr)
{
    osgActor::ActorNode& actor = static_cast<osgActor::ActorNode&>(object);
    bool advanced = false;
    std::string error;
    if (atLines(fr, "Definition"))
    {
        if (!osgActor::readWholeActorLines(actor, readBlockTokens(fr), "definition of actor '" + actor.getName() + "'",
                                           error))
            OSG_WARN << "osgActor: " << error << std::endl;
        advanced = true;
    }
    osg::ref_ptr<osgActor::ActorDefinitionObject> definition;
    if (readObjectBlock(fr, "DefinitionObject", definition))
    {
        advanced = true;
        if (!definition || !definition->getDefinition())
        {
            OSG_WARN << "osgActor: actor '" << actor.getName() << "' has no definition" << std::endl;
        }
        else if (!actor.setDefinition(definition->getDefinition(), osgActor::ActorNode::BIND_EXISTING_SKELETON_NODES))
        {
            OSG_WARN << "osgActor: the skeleton nodes of actor '" << actor.getName()
                     << "' do not match its definition" << std::endl;
        }
    }
    osg::ref_ptr<osgActor::ClipLibraryObject> library;
    if (readObjectBlock(fr, "ClipLibraryObject", library))
    {
        advanced = true;
        if (library) actor.setClipLibrary(library->getLibrary());
    }
    if (atLines(fr, "Motion"))
    {
        if (!osgActor::readMotionLines(actor, readBlockTokens(fr), "motion of actor '" + actor.getName() + "'", error))
            OSG_WARN << "osgActor: " << error << std::endl;
        advanced = true;
    }
    if (fr.matchSequence("Dofs %i {"))
    {
        std::vector<double> values;
        bool valid = true;
        std::string problem;
        for (const std::string& token : readBlockTokens(fr))
        {
            values.emplace_back();
            if (!osgActor::parseNumber(token, values.back()) && valid)
            {
                valid = false;
                problem = osgActor::numberProblem(token);
            }
        }
        if (valid) actor.setDofs(values);
        else OSG_WARN << "osgActor: actor '" << actor.getName() << "' Dofs: " << problem << " (DOFs kept)" << std::endl;
        advanced = true;
    }
    osg::Vec3d translation;
    osg::Quat rotation;
    bool valid = false;
    if (readNumbersField(fr, "PreTranslation", translation.ptr(), 3, actor, valid))
    {
        if (valid) actor.setPreTranslation(translation);
        advanced = true;
    }
    if (readNumbersField(fr, "PreRotation", rotation._v, 4, actor, valid))
    {
        if (valid) actor.setPreRotation(rotation);
        advanced = true;
    }
    if (readNumbersField(fr, "PostTranslation", translation.ptr(), 3, actor, valid))
    {
        if (valid) actor.setPostTranslation(translation);
        advanced = true;
    }
    if (readNumbersField(fr, "PostRotation", rotation._v, 4, actor, valid))
    {
        if (valid) actor.setPostRotation(rotation);
        advanced = true;
    }
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
        writeObjectBlock(fw, "DefinitionObject", actor.getDefinitionObject());
        writeObjectBlock(fw, "ClipLibraryObject", actor.getClipLibraryObject());
        const std::vector<std::string> motion = osgActor::writeMotionLines(actor);
        if (!motion.empty()) writeLines(fw, "Motion", motion);

        fw.indent() << "Dofs " << actor.getNumDofs() << " {" << std::endl;
        fw.moveIn();
        for (const double value : actor.getDofs()) fw.indent() << osgActor::formatNumber(value) << std::endl;
        fw.moveOut();
        fw.indent() << "}" << std::endl;
    }
    writeNumbersField(fw, "PreTranslation", actor.getPreTranslation().ptr(), 3);
    writeNumbersField(fw, "PreRotation", actor.getPreRotation()._v, 4);
    writeNumbersField(fw, "PostTranslation", actor.getPostTranslation().ptr(), 3);
    writeNumbersField(fw, "PostRotation", actor.getPostRotation()._v, 4);
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
