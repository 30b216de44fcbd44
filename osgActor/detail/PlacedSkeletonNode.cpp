#include <osgActor/detail/PlacedSkeletonNode.h>

#include <atomic>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

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

/** A block of nodes: this header, then one slot per node, each a whole number of cache lines. */
struct Block
{
    /** Slots in use by a node, plus one while the batch that fills the block lives. */
    std::atomic<std::size_t> live;
};

/** Each node is preceded by the block it lies in (null: a node allocated on its own), in the bytes between a
  * cache-line boundary and the node's address that put its matrix at the next boundary. */
std::size_t placementPad()
{
    static const std::size_t pad = [] {
        std::size_t bytes = (kCacheLine - matrixOffset() % kCacheLine) % kCacheLine;
        while (bytes < sizeof(Block*)) bytes += kCacheLine;
        return bytes;
    }();
    return pad;
}

Block*& blockBefore(void* node) { return *reinterpret_cast<Block**>(static_cast<char*>(node) - sizeof(Block*)); }

/** The batch of this thread: its block, where its next slot is, how many are left. */
struct CurrentBatch
{
    Block* block = nullptr;
    char* next = nullptr;
    std::size_t slotsLeft = 0;
    std::size_t slotSize = 0;
};
thread_local CurrentBatch current;

/** Memory for a block of size bytes, aligned to a cache line. A block of huge pages' size or more is aligned to one
  * and, where the system lends transparent huge pages on request, asks for them over its whole huge pages: a large
  * actor's nodes are then mapped by a fault per huge page rather than one per small page, each page zeroed by the
  * system once either way. */
void* allocateBlock(std::size_t size)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr std::size_t kHugePage = std::size_t(2) << 20;
    if (size >= kHugePage)
    {
        void* memory = nullptr;
        if (posix_memalign(&memory, kHugePage, size) != 0) return nullptr;
        // Advice only: refused (no huge pages here), the block keeps small pages.
        madvise(memory, size / kHugePage * kHugePage, MADV_HUGEPAGE);
        return memory;
    }
#endif
    return std::aligned_alloc(kCacheLine, size);
}

/** Gives the block back once the last count of its slots is released. */
void release(Block* block, std::size_t count)
{
    if (block->live.fetch_sub(count, std::memory_order_acq_rel) == count)
    {
        block->~Block();
        std::free(block);
    }
}

} // namespace

PlacedSkeletonNode::Batch::Batch(std::size_t count)
{
    if (count == 0 || current.block) return;
    // The slot fits the largest node made in it: the class's, which operator new is asked for (checked there).
    const std::size_t slotSize =
        (placementPad() + sizeof(PlacedSkeletonNode) + kCacheLine - 1) / kCacheLine * kCacheLine;
    const std::size_t headerSize = (sizeof(Block) + kCacheLine - 1) / kCacheLine * kCacheLine;
    void* memory = allocateBlock(headerSize + count * slotSize);
    if (!memory) return; // the nodes are then allocated one by one
    current.block = new (memory) Block;
    current.block->live.store(count + 1, std::memory_order_relaxed);
    current.next = static_cast<char*>(memory) + headerSize;
    current.slotsLeft = count;
    current.slotSize = slotSize;
    _made = true;
}

PlacedSkeletonNode::Batch::~Batch()
{
    if (!_made) return;
    // The slots not used, and the batch's own count.
    release(current.block, current.slotsLeft + 1);
    current = CurrentBatch();
}

void* PlacedSkeletonNode::operator new(std::size_t size)
{
    const std::size_t pad = placementPad();
    if (current.slotsLeft > 0 && pad + size <= current.slotSize)
    {
        void* node = current.next + pad;
        blockBefore(node) = current.block;
        current.next += current.slotSize;
        --current.slotsLeft;
        return node;
    }
    const std::size_t blockSize = (size + pad + kCacheLine - 1) / kCacheLine * kCacheLine;
    void* block = std::aligned_alloc(kCacheLine, blockSize);
    if (!block) throw std::bad_alloc();
    void* node = static_cast<char*>(block) + pad;
    blockBefore(node) = nullptr;
    return node;
}

void PlacedSkeletonNode::operator delete(void* node)
{
    if (!node) return;
    if (Block* block = blockBefore(node)) release(block, 1);
    else std::free(static_cast<char*>(node) - placementPad());
}

} // namespace detail
} // namespace osgActor
