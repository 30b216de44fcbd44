// ActorGroup::computeBound(): the actors' bounds computed on the group's threads where every bound written is the
// actor's own, and on the calling thread otherwise (a node shared between actors, a callback computing a bound).
// Run under ThreadSanitizer by scripts/test-sanitizers.sh.
#include "NodeTestUtil"

#include <osgActor/ActorGroup>

#include <cmath>
#include <cstring>
#include <thread>

using namespace osgActor;
using namespace osgActor::test;

namespace {

bool sameBits(const osg::BoundingSphere& a, const osg::BoundingSphere& b)
{
    return std::memcmp(&a, &b, sizeof(osg::BoundingSphere)) == 0;
}

/** A group whose bound computations note the thread that ran them (plain members: two threads computing it at once
  * is a race ThreadSanitizer reports). */
class ThreadNotingGroup : public osg::Group
{
public:
    osg::BoundingSphere computeBound() const override
    {
        ++computations;
        thread = std::this_thread::get_id();
        return osg::Group::computeBound();
    }
    mutable unsigned computations = 0;
    mutable std::thread::id thread;
};

/** The crowd of the tests: moving arms, half with bounds that follow the pose (every joint's bound dirtied at every
  * frame), every third one walking (its actor matrix changes at every frame), each with its own box at the tip. */
void fillCrowd(osg::Group& group, int numActors)
{
    for (int a = 0; a < numActors; ++a)
    {
        osg::ref_ptr<ActorNode> actor = new ActorNode(makePlanarArm());
        actor->addController(std::make_shared<SwingController>(0.1 * a));
        if (a % 2) actor->setBoundMode(ActorNode::BOUND_FOLLOWS_POSE);
        actor->getSkeletonNode("tip")->addChild(makeBox(osg::Vec3(0.2f, 0.0f, 0.0f), 0.1f).get());
        actor->setPreTranslation(osg::Vec3d(a % 7, a / 7, 0.0));
        group.addChild(actor.get());
    }
}

void walk(osg::Group& group, unsigned frame)
{
    for (unsigned a = 0; a < group.getNumChildren(); a += 3)
        static_cast<ActorNode*>(group.getChild(a))->setPreTranslation(osg::Vec3d(a % 7 + 0.01 * frame, a / 7, 0.0));
}

} // namespace

TEST(ActorGroupBounds, AreThoseOfTheSerialComputationBitForBit)
{
    osg::ref_ptr<ActorGroup> parallel = new ActorGroup;
    parallel->setNumThreads(2);
    parallel->setMinActorsForParallelCull(1);
    osg::ref_ptr<ActorGroup> serial = new ActorGroup;
    serial->setNumThreads(1);
    fillCrowd(*parallel, 40);
    fillCrowd(*serial, 40);
    for (unsigned frame = 1; frame <= 12; ++frame)
    {
        walk(*parallel, frame);
        walk(*serial, frame);
        runUpdate(*parallel, frame);
        runUpdate(*serial, frame);
        ASSERT_TRUE(sameBits(parallel->getBound(), serial->getBound())) << "frame " << frame;
        for (unsigned a = 0; a < parallel->getNumChildren(); ++a)
        {
            const ActorNode& p = static_cast<const ActorNode&>(*parallel->getChild(a));
            const ActorNode& s = static_cast<const ActorNode&>(*serial->getChild(a));
            EXPECT_TRUE(sameBits(p.getBound(), s.getBound())) << "frame " << frame << ", actor " << a;
            for (unsigned j = 0; j < p.getNumSkeletonNodes(); ++j)
                EXPECT_TRUE(sameBits(p.getSkeletonNode(j)->getBound(), s.getSkeletonNode(j)->getBound()))
                    << "frame " << frame << ", actor " << a << ", joint " << j;
        }
    }
    EXPECT_FALSE(sameBits(parallel->getBound(), osg::BoundingSphere())) << "the crowd has a bound";
}

TEST(ActorGroupBounds, LeaveANodeSharedByActorsToTheCallingThread)
{
    // One node under every actor's tip, its bound dirtied at every frame: every actor's bound then asks it, and only
    // one thread may compute it.
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    group->setMinActorsForParallelCull(1);
    fillCrowd(*group, 32);
    osg::ref_ptr<ThreadNotingGroup> shared = new ThreadNotingGroup;
    shared->addChild(makeBox(osg::Vec3(0.0f, 0.3f, 0.0f), 0.05f).get());
    for (unsigned a = 0; a < group->getNumChildren(); ++a)
        static_cast<ActorNode*>(group->getChild(a))->getSkeletonNode("tip")->addChild(shared.get());
    for (unsigned frame = 1; frame <= 20; ++frame)
    {
        shared->dirtyBound();
        walk(*group, frame);
        runUpdate(*group, frame);
        const unsigned before = shared->computations;
        group->getBound();
        EXPECT_EQ(shared->computations, before + 1) << "frame " << frame;
        EXPECT_EQ(shared->thread, std::this_thread::get_id()) << "frame " << frame;
    }
}

TEST(ActorGroupBounds, LeaveJointsWithBoundCallbacksToTheCallingThread)
{
    struct NotingCallback : osg::Node::ComputeBoundingSphereCallback
    {
        osg::BoundingSphere computeBound(const osg::Node& node) const override
        {
            thread = std::this_thread::get_id();
            return static_cast<const SkeletonNode&>(node).SkeletonNode::computeBound();
        }
        mutable std::thread::id thread;
    };
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(2);
    group->setMinActorsForParallelCull(1);
    fillCrowd(*group, 32);
    std::vector<osg::ref_ptr<NotingCallback>> callbacks;
    for (unsigned a = 1; a < group->getNumChildren(); a += 2) // bounds that follow the pose: dirtied every frame
    {
        callbacks.push_back(new NotingCallback);
        static_cast<ActorNode*>(group->getChild(a))->getSkeletonNode("base")->setComputeBoundingSphereCallback(
            callbacks.back().get());
    }
    for (unsigned frame = 1; frame <= 10; ++frame)
    {
        runUpdate(*group, frame);
        group->getBound();
        for (std::size_t c = 0; c < callbacks.size(); ++c)
            EXPECT_EQ(callbacks[c]->thread, std::this_thread::get_id()) << "frame " << frame << ", callback " << c;
    }
}
