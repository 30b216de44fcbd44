/* osgActor::ActorDefinitionObject in the .osg format: the definition's joints as a .actor text, one quoted string per
 * line. Every actor of the definition refers to this one object ("Use <id>"). */
#include "DotOsgBlocks"

#include <osgActor/ActorDefinitionObject>
#include <osgActor/ActorPartsText>

#include <osg/Notify>
#include <osgDB/Registry>

using namespace osgActorDotOsg;

namespace {

bool readActorDefinitionObject(osg::Object& object, osgDB::Input& fr)
{
    if (!atLines(fr, "Definition")) return false;
    std::string error;
    osgActor::ActorDefinitionPtr definition =
        osgActor::readDefinitionLines(readBlockTokens(fr), "an actor definition", error);
    if (definition) static_cast<osgActor::ActorDefinitionObject&>(object).setDefinition(std::move(definition));
    else OSG_WARN << "osgActor: " << error << std::endl;
    return true;
}

bool writeActorDefinitionObject(const osg::Object& object, osgDB::Output& fw)
{
    const auto& wrapper = static_cast<const osgActor::ActorDefinitionObject&>(object);
    if (wrapper.getDefinition()) writeLines(fw, "Definition", osgActor::writeDefinitionLines(*wrapper.getDefinition()));
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ActorDefinitionObject)
(new osgActor::ActorDefinitionObject, "osgActor::ActorDefinitionObject", "Object osgActor::ActorDefinitionObject",
 &readActorDefinitionObject, &writeActorDefinitionObject, osgDB::DotOsgWrapper::READ_AND_WRITE);
