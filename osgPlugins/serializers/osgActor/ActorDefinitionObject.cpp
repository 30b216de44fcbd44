/* osgActor::ActorDefinitionObject in OSG's serializer formats (.osgt, .osgb, .osgx): the definition's joints as the
 * lines of a .actor file. Every actor of the definition refers to this one object (UniqueID). */
#include "SerializedLines"

#include <osgActor/ActorDefinitionObject>
#include <osgActor/ActorPartsText>

#include <osgDB/ObjectWrapper>

using namespace osgActorSerializers;

static bool checkDefinition(const osgActor::ActorDefinitionObject& object) { return object.getDefinition() != nullptr; }

static bool readDefinition(osgDB::InputStream& is, osgActor::ActorDefinitionObject& object)
{
    const std::vector<std::string> lines = readLines(is);
    if (is.getException()) return false;
    std::string error;
    osgActor::ActorDefinitionPtr definition = osgActor::readDefinitionLines(lines, "an actor definition", error);
    if (!definition) return failRead(is, error);
    object.setDefinition(std::move(definition));
    return true;
}

static bool writeDefinition(osgDB::OutputStream& os, const osgActor::ActorDefinitionObject& object)
{
    writeLines(os, osgActor::writeDefinitionLines(*object.getDefinition()));
    return true;
}

REGISTER_OBJECT_WRAPPER(osgActor_ActorDefinitionObject, new osgActor::ActorDefinitionObject,
                        osgActor::ActorDefinitionObject, "osg::Object osgActor::ActorDefinitionObject")
{
    ADD_USER_SERIALIZER(Definition);
}
