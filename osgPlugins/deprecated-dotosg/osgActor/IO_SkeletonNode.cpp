/* osgActor::SkeletonNode in the .osg format. Its matrix is MatrixTransform's. */
#include <osgActor/SkeletonNode>

#include <osgDB/Input>
#include <osgDB/Output>
#include <osgDB/Registry>

namespace {

bool readSkeletonNode(osg::Object& object, osgDB::Input& fr)
{
    osgActor::SkeletonNode& node = static_cast<osgActor::SkeletonNode&>(object);
    bool advanced = false;
    unsigned int index = 0;
    if (fr[0].matchWord("JointIndex") && fr[1].getUInt(index))
    {
        node.setJointIndex(index);
        fr += 2;
        advanced = true;
    }
    if (fr[0].matchWord("Hidden"))
    {
        node.setHidden(fr[1].matchWord("TRUE"));
        fr += 2;
        advanced = true;
    }
    return advanced;
}

bool writeSkeletonNode(const osg::Object& object, osgDB::Output& fw)
{
    const osgActor::SkeletonNode& node = static_cast<const osgActor::SkeletonNode&>(object);
    fw.indent() << "JointIndex " << node.getJointIndex() << std::endl;
    fw.indent() << "Hidden " << (node.getHidden() ? "TRUE" : "FALSE") << std::endl;
    return true;
}

} // namespace

REGISTER_DOTOSGWRAPPER(osgActor_SkeletonNode)
(new osgActor::SkeletonNode, "osgActor::SkeletonNode",
 "Object Node Transform MatrixTransform osgActor::SkeletonNode Group", &readSkeletonNode, &writeSkeletonNode,
 osgDB::DotOsgWrapper::READ_AND_WRITE);
