/* osgActor::ClipLibraryObject in OSG's serializer formats (.osgt, .osgb, .osgx): the definition the clips are
 * written for (the ActorDefinitionObject, by reference when it was written before), then the clips as .actor clip
 * sections, read against it. Every actor holding the library refers to this one object (UniqueID). */
#include "SerializedLines"

#include <osgActor/ActorPartsText>
#include <osgActor/ClipLibraryObject>

#include <osgDB/ObjectWrapper>

using namespace osgActorSerializers;

static bool checkClips(const osgActor::ClipLibraryObject& object) { return object.getLibrary() != nullptr; }

static bool readClips(osgDB::InputStream& is, osgActor::ClipLibraryObject& object)
{
    const std::vector<std::string> lines = readLines(is);
    if (is.getException()) return false;
    const osgActor::ActorDefinitionObject* definition = object.getDefinitionObject();
    if (!definition || !definition->getDefinition())
        return failRead(is, "a clip library without the definition its clips drive");
    std::string error;
    osgActor::ClipLibraryPtr library =
        osgActor::readClipLines(lines, definition->getDefinition(), "the clips of actor definition '" +
                                                                        definition->getDefinition()->getName() + "'",
                                error);
    if (!library) return failRead(is, error);
    object.setLibrary(std::move(library));
    return true;
}

static bool writeClips(osgDB::OutputStream& os, const osgActor::ClipLibraryObject& object)
{
    writeLines(os, osgActor::writeClipLines(*object.getLibrary()));
    return true;
}

REGISTER_OBJECT_WRAPPER(osgActor_ClipLibraryObject, new osgActor::ClipLibraryObject, osgActor::ClipLibraryObject,
                        "osg::Object osgActor::ClipLibraryObject")
{
    ADD_OBJECT_SERIALIZER(DefinitionObject, osgActor::ActorDefinitionObject, NULL); // first: the clips need it
    ADD_USER_SERIALIZER(Clips);
}
