/* osgActor::ClipLibraryObject in the .osg format: the definition the clips are written for (the
 * ActorDefinitionObject, or "Use <id>" when it was written before), then the clips as .actor clip sections, one
 * quoted string per line, read against it. Every actor holding the library refers to this one object. */
#include "DotOsgBlocks"

#include <osgActor/ActorPartsText>
#include <osgActor/ClipLibraryObject>

#include <osg/Notify>
#include <osgDB/Registry>

using namespace osgActorDotOsg;

namespace {

bool readClipLibraryObject(osg::Object& object, osgDB::Input& fr)
{
    auto& wrapper = static_cast<osgActor::ClipLibraryObject&>(object);
    bool advanced = false;
    osg::ref_ptr<osgActor::ActorDefinitionObject> definition;
    if (readObjectBlock(fr, "DefinitionObject", definition))
    {
        wrapper.setDefinitionObject(definition.get());
        advanced = true;
    }
    if (atLines(fr, "Clips"))
    {
        const std::vector<std::string> lines = readBlockTokens(fr);
        advanced = true;
        const osgActor::ActorDefinitionObject* clipsDefinition = wrapper.getDefinitionObject();
        if (!clipsDefinition || !clipsDefinition->getDefinition())
        {
            OSG_WARN << "osgActor: a clip library without the definition its clips drive" << std::endl;
            return advanced;
        }
        const osgActor::ActorDefinitionPtr& drives = clipsDefinition->getDefinition();
        std::string error;
        osgActor::ClipLibraryPtr library = osgActor::readClipLines(
            lines, drives, "the clips of actor definition '" + drives->getName() + "'", error);
        if (library) wrapper.setLibrary(std::move(library));
        else OSG_WARN << "osgActor: " << error << std::endl;
    }
    return advanced;
}

bool writeClipLibraryObject(const osg::Object& object, osgDB::Output& fw)
{
    const auto& wrapper = static_cast<const osgActor::ClipLibraryObject&>(object);
    writeObjectBlock(fw, "DefinitionObject", wrapper.getDefinitionObject());
    if (wrapper.getLibrary()) writeLines(fw, "Clips", osgActor::writeClipLines(*wrapper.getLibrary()));
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_ClipLibraryObject)
(new osgActor::ClipLibraryObject, "osgActor::ClipLibraryObject", "Object osgActor::ClipLibraryObject",
 &readClipLibraryObject, &writeClipLibraryObject, osgDB::DotOsgWrapper::READ_AND_WRITE);
