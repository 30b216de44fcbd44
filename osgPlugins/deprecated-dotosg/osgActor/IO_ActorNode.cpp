/* osgActor::ActorNode in the .osg format. Its fields follow osg::Group's children (the associates list puts
 * Group first), so reading the definition binds the skeleton nodes already read. The definition and the clip
 * library are written as shared objects (ActorDefinitionObject, ClipLibraryObject), which osgDB writes once and
 * then as "Use <id>"; the actor's own motion (players, trajectories, IK chains) as .actor text, one quoted string
 * per line (ActorPartsText). Files that hold a whole .actor text per actor ("Definition <n> { ... }", the form
 * written before) are still read. */
#include "DotOsgBlocks"
#include "DotOsgNumbers"

#include <osgActor/ActorNode>
#include <osgActor/ActorPartsText>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

using namespace osgActorDotOsg;

namespace {

bool readActorNode(osg::Object& object, osgDB::Input& fr);
bool writeActorNode(const osg::Object& object, osgDB::Output& fw);

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
        writeObjectBlock(fw, "DefinitionObject", actor.getDefinitionObject());
        writeObjectBlock(fw, "ClipLibraryObject", actor.getClipLibraryObject());
        const std::vector<std::string> motion = osgActor::writeMotionLines(actor);
        if (!motion.empty()) writeLines(fw, "Motion", motion);

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
