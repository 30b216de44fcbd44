/* osgActor::InstancedActorGroup in the .osg format: its draw mode and lights. Its thread count is ActorGroup's
 * wrapper's, its children osg::Group's. */
#include <osgActor/InstancedActorGroup>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

namespace {

bool readInstancedActorGroup(osg::Object& object, osgDB::Input& fr)
{
    osgActor::InstancedActorGroup& group = static_cast<osgActor::InstancedActorGroup&>(object);
    bool read = false;
    if (fr[0].matchWord("DrawMode") && (fr[1].matchWord("INSTANCED") || fr[1].matchWord("ORDINARY")))
    {
        group.setDrawMode(fr[1].matchWord("INSTANCED") ? osgActor::InstancedActorGroup::INSTANCED
                                                       : osgActor::InstancedActorGroup::ORDINARY);
        fr += 2;
        read = true;
    }
    unsigned int lights = 0;
    if (fr[0].matchWord("Lights") && fr[1].getUInt(lights) && lights <= 255)
    {
        group.setLights(static_cast<std::uint8_t>(lights));
        fr += 2;
        read = true;
    }
    return read;
}

bool writeInstancedActorGroup(const osg::Object& object, osgDB::Output& fw)
{
    const osgActor::InstancedActorGroup& group = static_cast<const osgActor::InstancedActorGroup&>(object);
    fw.indent() << "DrawMode "
                << (group.getDrawMode() == osgActor::InstancedActorGroup::INSTANCED ? "INSTANCED" : "ORDINARY")
                << std::endl;
    fw.indent() << "Lights " << static_cast<unsigned>(group.getLights()) << std::endl;
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_InstancedActorGroup)
(new osgActor::InstancedActorGroup, "osgActor::InstancedActorGroup",
 "Object Node Group osgActor::ActorGroup osgActor::InstancedActorGroup", &readInstancedActorGroup,
 &writeInstancedActorGroup, osgDB::DotOsgWrapper::READ_AND_WRITE);
