/* osgActor::ActorUpdateCallback in OSG's serializer formats (.osgt, .osgb, .osgx). It has no fields. */
#include <osgActor/ActorUpdateCallback>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgActor_ActorUpdateCallback, new osgActor::ActorUpdateCallback,
                        osgActor::ActorUpdateCallback,
                        "osg::Object osg::Callback osg::NodeCallback osgActor::ActorUpdateCallback")
{
    static_cast<void>(wrapper); // no fields to add
}
