// The update traversal of N osgActor humanoids, every joint moving (osgactorbench's update/osgActor_all scene and
// frame loop), or the update and the cull (its update_cull/osgActor_all; idle: update_cull/osgActor_idle), for instruction and cache-miss counts under callgrind, which are repeatable where wall-clock time on a
// shared machine is not. The warm-up frames (the players bind their channels on the first) run uninstrumented; the
// measured frames run between callgrind's client requests, so
//     valgrind --tool=callgrind --instr-atstart=no --cache-sim=yes --LL=1048576,16,64 build/bin/osgactor_frame_counts
// counts those frames only (outside valgrind the requests do nothing). Arguments: actors (1000), measured frames
// (20), then any of "follow" for bounds that follow the pose (the default covers rotations), "cull" for the cull
// too, "idle" for actors without a controller, "instanced" for the crowd under an InstancedActorGroup (its
// update_cull/osgActor_all_instanced, or _idle_instanced), "nearfar" for a cull computing near and far from bounding
// volumes as osgViewer's default camera does (update_cull_nearfar/osgActor_all, or _idle, _all_instanced,
// _idle_instanced), "threads=N" for the crowd's group (an ActorGroup, or the InstancedActorGroup) on N threads, its
// update and cull on them (callgrind runs the threads one at a time: --separate-threads=yes counts each one's share),
// "props" for a prop in each right hand (a user's group holding a box, traversed ordinarily below the joint),
// "inflight=N" for N frames in flight, the culls taking turns among N scene views each holding its render graph until
// its next cull (2: osgViewer's draw thread, DrawThreadPerContext; an InstancedActorGroup's frames alternate).
// Divide the counts by actors x frames x 31 joints for figures per joint and frame (docs/performance.md).
#include "FrameLoop"
#include "PeerScenes"

#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

int main(int argc, char** argv)
{
    const unsigned numActors = argc > 1 ? static_cast<unsigned>(std::atoi(argv[1])) : 1000u;
    const unsigned numFrames = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 20u;
    bool follow = false, cull = false, idle = false, instanced = false, nearFar = false, props = false;
    unsigned threads = 0, framesInFlight = 1;
    for (int i = 3; i < argc; ++i)
    {
        if (std::strncmp(argv[i], "threads=", 8) == 0) threads = static_cast<unsigned>(std::atoi(argv[i] + 8));
        if (std::strncmp(argv[i], "inflight=", 9) == 0) framesInFlight = static_cast<unsigned>(std::atoi(argv[i] + 9));
        follow = follow || std::strcmp(argv[i], "follow") == 0;
        cull = cull || std::strcmp(argv[i], "cull") == 0;
        idle = idle || std::strcmp(argv[i], "idle") == 0;
        instanced = instanced || std::strcmp(argv[i], "instanced") == 0;
        nearFar = nearFar || std::strcmp(argv[i], "nearfar") == 0;
        props = props || std::strcmp(argv[i], "props") == 0;
    }
    if (numActors == 0 || numFrames == 0 || framesInFlight == 0)
    {
        std::fprintf(stderr,
                     "usage: %s [actors > 0] [frames > 0] [follow] [cull] [idle] [instanced] [nearfar] [props] [threads=N] "
                     "[inflight=N > 0]\n",
                     argv[0]);
        return 1;
    }
    bench::OsgActorCrowd crowd;
    crowd.motion = idle ? bench::Motion::Idle : bench::Motion::All;
    crowd.bounds = follow ? bench::Bounds::FollowPose : bench::Bounds::CoverRotations;
    crowd.instanced = instanced;
    crowd.props = props;
    crowd.threads = threads;
    osg::ref_ptr<osg::Group> scene = bench::makeOsgActorScene(numActors, crowd);
    bench::FrameLoop loop(scene.get(), cull,
                          nearFar ? bench::FrameLoop::NearFar::FromBoundingVolumes : bench::FrameLoop::NearFar::NotComputed,
                          framesInFlight);
    for (int i = 0; i < 10; ++i) loop.frame();
    CALLGRIND_ZERO_STATS;
    CALLGRIND_START_INSTRUMENTATION;
    for (unsigned i = 0; i < numFrames; ++i) loop.frame();
    CALLGRIND_STOP_INSTRUMENTATION;
    CALLGRIND_DUMP_STATS_AT("measured frames");
    std::printf("%u actors, %u measured frames\n", numActors, numFrames);
    if (cull && nearFar) std::printf("near %.9g, far %.9g computed\n", loop.lastNear(), loop.lastFar());
    return 0;
}
