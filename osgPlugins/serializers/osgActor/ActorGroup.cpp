/* osgActor::ActorGroup in OSG's serializer formats (.osgt, .osgb, .osgx). Its children, the actors among them, are
 * osg::Group's; its update callback is osg::Node's (ActorGroupUpdateCallback). */
#include <osgActor/ActorGroup>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgActor_ActorGroup, new osgActor::ActorGroup, osgActor::ActorGroup,
                        "osg::Object osg::Node osg::Group osgActor::ActorGroup")
{
    ADD_UINT_SERIALIZER(NumThreads, 0u); // threads counting the update thread; 0: one per hardware thread
}
