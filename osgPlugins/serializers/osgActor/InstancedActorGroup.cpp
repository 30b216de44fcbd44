/* osgActor::InstancedActorGroup in OSG's serializer formats (.osgt, .osgb, .osgx): its draw mode and lights; its
 * thread count is ActorGroup's, its children osg::Group's. */
#include <osgActor/InstancedActorGroup>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgActor_InstancedActorGroup, new osgActor::InstancedActorGroup,
                        osgActor::InstancedActorGroup,
                        "osg::Object osg::Node osg::Group osgActor::ActorGroup osgActor::InstancedActorGroup")
{
    BEGIN_ENUM_SERIALIZER(DrawMode, INSTANCED);
        ADD_ENUM_VALUE(INSTANCED);
        ADD_ENUM_VALUE(ORDINARY);
    END_ENUM_SERIALIZER();
    ADD_UCHAR_SERIALIZER(Lights, 1); // a bit per light, 1 << i for GL_LIGHTi
}
