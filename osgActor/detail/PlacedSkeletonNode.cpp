#include <osgActor/detail/PlacedSkeletonNode.h>

#include <cstdlib>
#include <new>

namespace osgActor {
namespace detail {

namespace {

constexpr std::size_t kCacheLine = 64;

/** Bytes from a node's address to its matrix, measured once on a plain SkeletonNode (the class adds no member, so
  * the layout is the same). */
std::size_t matrixOffset()
{
    static const std::size_t offset = [] {
        osg::ref_ptr<SkeletonNode> probe = new SkeletonNode;
        return static_cast<std::size_t>(reinterpret_cast<const char*>(probe->getMatrix().ptr()) -
                                        reinterpret_cast<const char*>(probe.get()));
    }();
    return offset;
}

/** Bytes between a cache-line boundary and the node's address that put its matrix at the next boundary. */
std::size_t placementPad() { return (kCacheLine - matrixOffset() % kCacheLine) % kCacheLine; }

} // namespace

void* PlacedSkeletonNode::operator new(std::size_t size)
{
    const std::size_t pad = placementPad();
    const std::size_t blockSize = (size + pad + kCacheLine - 1) / kCacheLine * kCacheLine;
    void* block = std::aligned_alloc(kCacheLine, blockSize);
    if (!block) throw std::bad_alloc();
    return static_cast<char*>(block) + pad;
}

void PlacedSkeletonNode::operator delete(void* node)
{
    if (node) std::free(static_cast<char*>(node) - placementPad());
}

} // namespace detail
} // namespace osgActor
