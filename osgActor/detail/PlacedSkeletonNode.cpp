#include <osgActor/detail/PlacedSkeletonNode.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
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

} // namespace

// A block from malloc() with room to place the node in, and the block's address kept just below the node, rather
// than a block from aligned_alloc(): glibc makes an aligned block by carving a larger one and filing the pieces
// left over in its bins, several times malloc()'s work, and the next allocations then sort through those pieces.
void* PlacedSkeletonNode::operator new(std::size_t size)
{
    static_assert(alignof(SkeletonNode) <= alignof(void*), "a node placed at any multiple of a pointer's size");
    const std::uintptr_t matrixInLine = matrixOffset() % kCacheLine;
    void* const block = std::malloc(sizeof(void*) + kCacheLine - 1 + size);
    if (!block) throw std::bad_alloc();
    // The lowest address past the kept pointer whose matrix starts a cache line.
    const std::uintptr_t lowest = reinterpret_cast<std::uintptr_t>(block) + sizeof(void*);
    const std::uintptr_t node = (lowest + matrixInLine + kCacheLine - 1) / kCacheLine * kCacheLine - matrixInLine;
    std::memcpy(reinterpret_cast<void*>(node - sizeof(void*)), &block, sizeof block);
    return reinterpret_cast<void*>(node);
}

void PlacedSkeletonNode::operator delete(void* node)
{
    if (!node) return;
    void* block;
    std::memcpy(&block, static_cast<const char*>(node) - sizeof(void*), sizeof block);
    std::free(block);
}

} // namespace detail
} // namespace osgActor
