#include <osgActor/ActorDefinitionObject>

#include "SharedObjectRegistry.h"

namespace osgActor {

namespace {

const ActorDefinition* definitionOf(const ActorDefinitionObject& object) { return object.getDefinition().get(); }

using DefinitionRegistry = SharedObjectRegistry<const ActorDefinition*, ActorDefinitionObject, &definitionOf>;

DefinitionRegistry& registry()
{
    static DefinitionRegistry wrappers;
    return wrappers;
}

} // namespace

ActorDefinitionObject::ActorDefinitionObject(const ActorDefinitionObject& object, const osg::CopyOp& copyop)
    : osg::Object(object, copyop), _definition(object._definition)
{
}

osg::ref_ptr<ActorDefinitionObject> ActorDefinitionObject::of(const ActorDefinitionPtr& definition)
{
    if (!definition) return nullptr;
    return registry().findOrMake(definition.get(), [&definition]() {
        osg::ref_ptr<ActorDefinitionObject> made = new ActorDefinitionObject;
        made->_definition = definition;
        return made;
    });
}

void ActorDefinitionObject::setDefinition(ActorDefinitionPtr definition)
{
    _definition = std::move(definition);
    if (_definition) registry().offer(*this);
}

} // namespace osgActor
