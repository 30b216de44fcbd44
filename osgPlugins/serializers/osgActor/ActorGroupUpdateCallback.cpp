/* osgActor::ActorGroupUpdateCallback in OSG's serializer formats (.osgt, .osgb, .osgx). It has no fields. */
#include <osgActor/ActorGroup>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgActor_ActorGroupUpdateCallback, new osgActor::ActorGroupUpdateCallback,
                        osgActor::ActorGroupUpdateCallback,
                        "osg::Object osg::Callback osg::NodeCallback osgActor::ActorGroupUpdateCallback")
{
    static_cast<void>(wrapper); // no fields to add
}
