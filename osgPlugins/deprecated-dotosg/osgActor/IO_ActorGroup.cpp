/* osgActor::ActorGroup in the .osg format: its thread count. Its children are osg::Group's. */
#include <osgActor/ActorGroup>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

namespace {

bool readActorGroup(osg::Object& object, osgDB::Input& fr)
{
    unsigned int numThreads = 0;
    if (!fr[0].matchWord("NumThreads") || !fr[1].getUInt(numThreads)) return false;
    static_cast<osgActor::ActorGroup&>(object).setNumThreads(numThreads);
    fr += 2;
    return true;
}

bool writeActorGroup(const osg::Object& object, osgDB::Output& fw)
{
    fw.indent() << "NumThreads " << static_cast<const osgActor::ActorGroup&>(object).getNumThreads() << std::endl;
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ActorGroup)
(new osgActor::ActorGroup, "osgActor::ActorGroup", "Object Node Group osgActor::ActorGroup", &readActorGroup,
 &writeActorGroup, osgDB::DotOsgWrapper::READ_AND_WRITE);
