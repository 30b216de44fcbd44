// Internal to the library (not installed, NOT API): the skeleton nodes an ActorNode builds for itself, placed in
// memory so that their matrix starts a cache line. A 16-double matrix then spans two lines rather than three (as it
// does for three nodes in four otherwise), so an actor's per-frame write of its joints' matrices touches fewer lines
// when many actors no longer fit in cache (docs/performance.md). A SkeletonNode in every other respect: it adds no
// member and no behaviour, keeps SkeletonNode's class name for osgDB, and clones as a plain SkeletonNode.
//
// The nodes an actor builds at once are placed side by side in one block of memory (a Batch): one allocation
// instead of one per node, each node's lines next to the previous one's; a block of a huge page or more is advised to
// take huge pages, so a large actor's build faults its memory in once per huge page rather than once per small page.
// The block is given back when the last of its nodes is deleted, whichever thread deletes it.
#ifndef OSGACTOR_DETAIL_PLACEDSKELETONNODE_H
#define OSGACTOR_DETAIL_PLACEDSKELETONNODE_H 1

#include <osgActor/SkeletonNode>

#include <cstddef>

namespace osgActor {
namespace detail {

class PlacedSkeletonNode : public SkeletonNode
{
public:
    PlacedSkeletonNode(unsigned jointIndex, const std::string& jointName) : SkeletonNode(jointIndex, jointName) {}
    PlacedSkeletonNode(const SkeletonNode& node, const osg::CopyOp& copyop) : SkeletonNode(node, copyop) {}

    /** While it lives, the nodes made on this thread (up to count) are placed in one block, in the order they are
      * made; past count, or without a batch, each has an allocation of its own. A batch made while another lives
      * on the thread does nothing. */
    class Batch
    {
    public:
        explicit Batch(std::size_t count);
        ~Batch();
        Batch(const Batch&) = delete;
        Batch& operator=(const Batch&) = delete;

    private:
        /** Whether this batch made the thread's block (not when one was there already). */
        bool _made = false;
    };

    static void* operator new(std::size_t size);
    static void operator delete(void* node);

protected:
    ~PlacedSkeletonNode() override = default;
};

} // namespace detail
} // namespace osgActor

#endif
