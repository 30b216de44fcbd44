// RetargetJob's instructions per frame (issue 27), for callgrind, whose counts the machine's load does not move where
// the clock's do: CMU's 12_03.bvh (31 joints) retargeted onto one of the timing benchmark's targets (0: itself, 1: the
// humanoid, 2: Boxing_Toes, 3: Cesium Man), the whole clip once uninstrumented (caches and branch history warm), then
// the clip `passes` times (2 unless given) between callgrind's client requests, so
//     valgrind --tool=callgrind --instr-atstart=no build/bin/osgactor_retarget_counts 1
// counts the measured passes only (outside valgrind the requests do nothing). Divide the count by the frames printed.
#include "RetargetBenchTargets.h"

#include <valgrind/callgrind.h>

#include <cstdio>
#include <cstdlib>

using namespace osgActor;

int main(int argc, char** argv)
{
    const int which = argc > 1 ? std::atoi(argv[1]) : 1;
    const int passes = argc > 2 ? std::atoi(argv[2]) : 2;
    if (which < 0 || which >= bench::kNumTargets || passes <= 0)
    {
        std::fprintf(stderr, "usage: %s [target 0-%d] [passes > 0]\n", argv[0], bench::kNumTargets - 1);
        return 1;
    }
    bench::RetargetJobOnto onto(which);
    const unsigned numFrames = onto.clip->getNumFrames();
    const auto pass = [&] {
        unsigned failed = 0;
        for (unsigned frame = 0; frame < numFrames; ++frame) failed += onto.runFrame(frame) ? 0 : 1;
        return failed;
    };
    unsigned failed = pass();
    CALLGRIND_START_INSTRUMENTATION;
    for (int p = 0; p < passes; ++p) failed += pass();
    CALLGRIND_STOP_INSTRUMENTATION;
    std::printf("%s: %u frames measured (%d passes of %u), %u runs failed\n", bench::kTargetNames[which],
                static_cast<unsigned>(passes) * numFrames, passes, numFrames, failed);
    return failed == 0 ? 0 : 1;
}
