#include <osgActor/ClipLibraryObject>

#include "SharedObjectRegistry.h"

#include <utility>

namespace osgActor {

namespace {

using LibraryKey = std::pair<const ClipLibrary*, const ActorDefinitionObject*>;

LibraryKey keyOf(const ClipLibraryObject& object)
{
    return LibraryKey(object.getLibrary().get(), object.getDefinitionObject());
}

using LibraryRegistry = SharedObjectRegistry<LibraryKey, ClipLibraryObject, &keyOf>;

LibraryRegistry& registry()
{
    static LibraryRegistry wrappers;
    return wrappers;
}

} // namespace

ClipLibraryObject::ClipLibraryObject(const ClipLibraryObject& object, const osg::CopyOp& copyop)
    : osg::Object(object, copyop), _library(object._library), _definitionObject(object._definitionObject)
{
}

osg::ref_ptr<ClipLibraryObject> ClipLibraryObject::of(const ClipLibraryPtr& library,
                                                      const ActorDefinitionObject* definition)
{
    if (!library || !definition) return nullptr;
    return registry().findOrMake(LibraryKey(library.get(), definition), [&library, definition]() {
        osg::ref_ptr<ClipLibraryObject> made = new ClipLibraryObject;
        made->_library = library;
        made->_definitionObject = definition;
        return made;
    });
}

void ClipLibraryObject::setDefinitionObject(ActorDefinitionObject* definition)
{
    _definitionObject = definition;
    offerToRegistry();
}

void ClipLibraryObject::setLibrary(ClipLibraryPtr library)
{
    _library = std::move(library);
    offerToRegistry();
}

void ClipLibraryObject::offerToRegistry()
{
    if (_library && _definitionObject.valid()) registry().offer(*this);
}

} // namespace osgActor
