/* Soak test (ctest label "long"): thousands of frames of a parallel ActorGroup with random DOF writes (NaN and inf
 * among them), clip switches and cross-fades, hides, clones and removals, and IK goals of every kind on every actor
 * (SoakIk). Every frame: no NaN or inf in any skeleton-node matrix, every DOF within its limits, the IK controllers
 * sane. After a warm-up, the heap in use must not grow. */
#include "RobustnessUtil"
#include "SoakIk"
#include "nodes/NodeTestUtil"

#include <osgActor/ActorGroup>

#include <gtest/gtest.h>

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

using namespace osgActor;
using namespace osgActor::test;

namespace {

const unsigned kActors = 48;

/** 20000 frames; OSGACTOR_SOAK_FRAMES makes the run shorter under ThreadSanitizer (scripts/test-sanitizers.sh). */
unsigned numFrames()
{
    const char* frames = std::getenv("OSGACTOR_SOAK_FRAMES");
    return frames ? static_cast<unsigned>(std::max(8l, std::atol(frames))) : 20000u;
}

bool matrixIsFinite(const osg::Matrixd& m)
{
    for (int i = 0; i < 16; ++i)
        if (!std::isfinite(m.ptr()[i])) return false;
    return true;
}

/** Bytes the allocator has handed out and not got back (glibc). */
size_t heapInUse()
{
    return mallinfo2().uordblks;
}

/** The actor's one ClipPlayer. */
std::shared_ptr<ClipPlayer> playerOf(ActorNode& actor)
{
    return std::dynamic_pointer_cast<ClipPlayer>(actor.findController("player"));
}

/** A new actor like the prototype (sharing its geometry) playing clip. */
osg::ref_ptr<ActorNode> makeActor(const ActorNode& prototype, const ClipPtr& clip)
{
    osg::ref_ptr<ActorNode> actor = osg::clone(&prototype, osg::CopyOp::SHALLOW_COPY);
    addPlayer(*actor, clip);
    return actor;
}

/** The actors of the group (all its children are actors). */
std::vector<ActorNode*> actorsOf(ActorGroup& group)
{
    std::vector<ActorNode*> actors;
    for (unsigned c = 0; c < group.getNumChildren(); ++c) actors.push_back(static_cast<ActorNode*>(group.getChild(c)));
    return actors;
}

} // namespace

TEST(Soak, ManyActorsManyFramesNoNaNWithinLimitsNoGrowth)
{
    const osg::ref_ptr<ActorNode> prototype = readHumanoid();
    const ActorDefinitionPtr definition = prototype->getDefinition();
    std::mt19937 random(20261121);
    std::vector<ClipPtr> clips;
    for (int c = 0; c < 6; ++c) clips.push_back(makeRandomClip(*definition, random, c));

    // The scene: the actors under their group, and beside them the nodes IK goals follow.
    osg::ref_ptr<osg::Group> scene = new osg::Group;
    osg::ref_ptr<ActorGroup> group = new ActorGroup;
    group->setNumThreads(4);
    scene->addChild(group);
    SoakIk ik(definition, *scene, random);
    for (unsigned a = 0; a < kActors; ++a)
    {
        group->addChild(makeActor(*prototype, clips[a % clips.size()]));
        ik.equip(*static_cast<ActorNode*>(group->getChild(a)));
    }

    const double specials[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::max(), -1e300};
    std::uniform_real_distribution<double> wide(-10.0, 10.0);
    const unsigned frames = numFrames();
    const unsigned warmUpFrames = frames / 4;
    size_t heapAfterWarmUp = 0;
    size_t refusedWrites = 0;

    for (unsigned frame = 1; frame <= frames; ++frame)
    {
        ActorNode* actor = static_cast<ActorNode*>(group->getChild(random() % group->getNumChildren()));
        const unsigned dof = random() % actor->getNumDofs();
        switch (random() % 10)
        {
        case 0: // a DOF write that must be refused and leave the value as it was
        {
            const double before = actor->getDof(dof);
            EXPECT_FALSE(actor->setDof(dof, specials[random() % 3]));
            EXPECT_EQ(actor->getDof(dof), before);
            ++refusedWrites;
            break;
        }
        case 1: // a huge or ordinary write: clamped to the limits
            actor->setDof(dof, random() % 2 ? specials[3 + random() % 2] : wide(random));
            break;
        case 2: // clip switch, or a cross-fade to a second player
            if (random() % 2)
                playerOf(*actor)->setClip(clips[random() % clips.size()]);
            else
            {
                auto next = std::make_shared<ClipPlayer>(clips[random() % clips.size()]);
                next->play();
                crossFade(*playerOf(*actor), *next, 0.2);
                actor->removeController(actor->findController("player"));
                next->setName("player");
                actor->addController(next);
                SoakIk::moveLast(*actor); // IK stays on top of the clip
            }
            break;
        case 3:
            playerOf(*actor)->setSpeed(wide(random));
            break;
        case 4: // hide or show a joint
        {
            SkeletonNode* node = actor->getSkeletonNode(random() % actor->getNumSkeletonNodes());
            node->setHidden(!node->getHidden());
            break;
        }
        case 5: // a clone replaces another actor: the count stays the same
        {
            osg::ref_ptr<ActorNode> twin = osg::clone(actor, osg::CopyOp::SHALLOW_COPY);
            group->removeChild(random() % group->getNumChildren());
            group->addChild(twin.get());
            break;
        }
        case 6: // a removal and a new actor
            group->removeChild(random() % group->getNumChildren());
            group->addChild(makeActor(*prototype, clips[random() % clips.size()]));
            break;
        case 7:
            actor->setPreTranslation(osg::Vec3d(wide(random), wide(random), 0.0));
            break;
        default: // an IK goal (valid or not), a chain or solver switch, a goal node moved, hidden or deleted
            ik.randomAction(*actor, actorsOf(*group));
            break;
        }

        if (frame % 4 == 0) ik.newGoals(actorsOf(*group), 6); // goals move every few frames

        runUpdate(*scene, frame);
        ik.checkAfterFrame(actorsOf(*group), frame);
        if (::testing::Test::HasFatalFailure()) return;

        for (unsigned c = 0; c < group->getNumChildren(); ++c)
        {
            const ActorNode* a = static_cast<const ActorNode*>(group->getChild(c));
            ASSERT_TRUE(matrixIsFinite(a->getMatrix())) << "frame " << frame << " actor " << c;
            for (unsigned j = 0; j < a->getNumSkeletonNodes(); ++j)
                ASSERT_TRUE(matrixIsFinite(a->getSkeletonNode(j)->getMatrix()))
                    << "frame " << frame << " actor " << c << " joint " << j;
            for (unsigned d = 0; d < a->getNumDofs(); ++d)
            {
                ASSERT_GE(a->getDof(d), definition->getDofMin(d)) << "frame " << frame << " dof " << d;
                ASSERT_LE(a->getDof(d), definition->getDofMax(d)) << "frame " << frame << " dof " << d;
            }
        }
        if (frame == warmUpFrames) heapAfterWarmUp = heapInUse();
    }
    EXPECT_GT(refusedWrites, 0u);
    // Every kind of IK event happened (at the TSan run's 400 frames too), and solves reached their goals.
    const SoakIkCounts& counts = ik.counts();
    EXPECT_GT(counts.goalsSet, 0u);
    EXPECT_GT(counts.goalsRefused, 0u);
    EXPECT_GT(counts.hugeGoals, 0u);
    EXPECT_GT(counts.chainSwitches, 0u);
    EXPECT_GT(counts.solvesReached, 0u);
    RecordProperty("ik_goals", counts.goalsSet);
    RecordProperty("ik_goal_nodes_deleted", counts.goalNodesDeleted);
    RecordProperty("ik_orphans_stopped", counts.orphansStopped);
    std::printf("IK: %u goals set, %u refused, %u huge, %u chain switches, %u goal nodes deleted, %u followers "
                "stopped, %u solves at their goal\n", counts.goalsSet, counts.goalsRefused, counts.hugeGoals,
                counts.chainSwitches, counts.goalNodesDeleted, counts.orphansStopped, counts.solvesReached);
    // The same number of actors, clips and controllers as after the warm-up: the heap may move by allocator slack
    // (vector capacities, OSG's caches), not by what thousands of frames would leak.
    const size_t heapAtEnd = heapInUse();
    EXPECT_LT(heapAtEnd, heapAfterWarmUp + heapAfterWarmUp / 10 + (1u << 20))
        << "heap in use grew from " << heapAfterWarmUp << " to " << heapAtEnd << " bytes";
}
