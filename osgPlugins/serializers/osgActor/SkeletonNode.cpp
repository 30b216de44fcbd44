/* osgActor::SkeletonNode in OSG's serializer formats (.osgt, .osgb, .osgx). Its matrix is MatrixTransform's. */
#include <osgActor/SkeletonNode>

#include <osgDB/ObjectWrapper>

REGISTER_OBJECT_WRAPPER(osgActor_SkeletonNode, new osgActor::SkeletonNode, osgActor::SkeletonNode,
                        "osg::Object osg::Node osg::Group osg::Transform osg::MatrixTransform osgActor::SkeletonNode")
{
    ADD_UINT_SERIALIZER(JointIndex, 0u); // the joint's index in the actor's definition
    ADD_BOOL_SERIALIZER(Hidden, false);  // the paper's hide flag
}
