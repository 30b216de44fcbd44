#include <osgActor/SkeletonNode>

#include <osgUtil/IntersectionVisitor>

namespace osgActor {

SkeletonNode::SkeletonNode() : _jointIndex(0), _hidden(false)
{
    // The matrix changes from frame to frame: keep osgUtil::Optimizer from flattening it away.
    setDataVariance(osg::Object::DYNAMIC);
}

SkeletonNode::SkeletonNode(unsigned jointIndex, const std::string& jointName) : SkeletonNode()
{
    _jointIndex = jointIndex;
    setName(jointName);
}

SkeletonNode::SkeletonNode(const SkeletonNode& node, const osg::CopyOp& copyop)
    : osg::MatrixTransform(node, copyop), _jointIndex(node._jointIndex), _hidden(node._hidden)
{
}

void SkeletonNode::traverse(osg::NodeVisitor& nv)
{
    if (_hidden && (nv.getVisitorType() == osg::NodeVisitor::CULL_VISITOR ||
                    dynamic_cast<osgUtil::IntersectionVisitor*>(&nv) != nullptr))
        return;
    osg::MatrixTransform::traverse(nv);
}

} // namespace osgActor
