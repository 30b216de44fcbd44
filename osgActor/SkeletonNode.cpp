#include <osgActor/SkeletonNode>

#include <osgUtil/IntersectionVisitor>

#include <cstddef>
#include <cstdlib>
#include <new>

namespace osgActor {

namespace {

constexpr std::size_t kCacheLine = 64;

} // namespace

std::size_t SkeletonNode::placementPad()
{
    // The node's address sits this many bytes past a cache-line boundary, so that its matrix (a member of
    // osg::MatrixTransform at a fixed offset) starts one. offsetof on a class that is not standard-layout is
    // conditionally supported; GCC and Clang compute it for single, non-virtual inheritance like this one.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Winvalid-offsetof"
    constexpr std::size_t matrixOffset = offsetof(SkeletonNode, _matrix);
#pragma GCC diagnostic pop
    return (kCacheLine - matrixOffset % kCacheLine) % kCacheLine;
}

void* SkeletonNode::operator new(std::size_t size)
{
    const std::size_t pad = placementPad();
    const std::size_t blockSize = (size + pad + kCacheLine - 1) / kCacheLine * kCacheLine;
    void* block = std::aligned_alloc(kCacheLine, blockSize);
    if (!block) throw std::bad_alloc();
    return static_cast<char*>(block) + pad;
}

void SkeletonNode::operator delete(void* node)
{
    if (node) std::free(static_cast<char*>(node) - placementPad());
}

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
