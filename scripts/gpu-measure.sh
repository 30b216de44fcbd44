#!/bin/sh
# The measurements that need a machine with a GPU and many cores (docs/performance.md, "On a GPU and 16 cores"), in
# one go, from a build made with scripts/build.sh, or from a bundle of it (scripts/bundle-for-gpu-host.sh) on a
# host without the project's packages:
#   1. the whole frame drawn on the GPU (osgactor_gpu_draw_bench: EGL, no display needed, every part drawn): rigid and
#      skinned crowds of 1000 against osgAnimation and plain OSG, and osgActor's GPU skinning against its CPU skinning
#      on that GPU (images); 10,000 under an ActorGroup and instanced, with osgViewer's draw thread and without
#      (osgAnimation's crowds of 10,000 take minutes to build: left out);
#   2. the update and cull of osgactorbench at 1000 actors, and the ActorGroup's update of 16,000 on 1, 2, 4, ...
#      threads up to the machine's cores (one crowd for the sweep: taking 16,000 apart costs minutes in OSG); the
#      update + cull of 1000 actors on the same thread counts, culled as one and instanced (issue 28's target);
#   3. CPU skinning, vertices per second on one core.
# Usage: scripts/gpu-measure.sh [BIN_DIR [OUT_DIR]]   (defaults: build/bin, gpu-measure)
# Writes OUT_DIR/measure.log (everything printed) and OUT_DIR/images.tar (the frames the GPU drew).
set -u
bin=$(cd "${1:-build/bin}" && pwd)
out=${2:-gpu-measure}
mkdir -p "$out/images"
out=$(cd "$out" && pwd)
root=$(cd "$(dirname "$0")/.." && pwd)
log="$out/measure.log"
if [ -e "$bin/../lib/libosgActor.so.0" ]; then # a bundle: its libraries and osgDB plugins beside its programs
    lib=$(cd "$bin/../lib" && pwd)
    export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" OSG_LIBRARY_PATH="$lib"
fi
cores=$(nproc)
threads=1
t=2
while [ "$t" -lt "$cores" ]; do threads="$threads,$t"; t=$((t * 2)); done
[ "$cores" -gt 1 ] && threads="$threads,$cores"

run() { echo "\$ $*" | tee -a "$log"; "$@" 2>&1 | tee -a "$log"; echo | tee -a "$log"; }

{
    date -u
    uname -srm
    grep -m1 'model name' /proc/cpuinfo
    echo "cores: $cores"
    command -v nvidia-smi >/dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader
} 2>&1 | tee "$log"
echo | tee -a "$log"

draw="$bin/osgactor_gpu_draw_bench --seconds=1.5 --small-features=draw --cesium-man=$root/data/models/CesiumMan/CesiumMan.gltf"
run timeout 150 $draw --actors=1000 --images="$out/images"
run timeout 90 $draw --actors=10000 --threading=draw \
    --systems=rigid_osgActor_group,rigid_osgActor_instanced_threaded,skinned_osgActor_instanced_threaded
run timeout 60 $draw --actors=10000 --systems=rigid_osgActor_instanced,rigid_osgActor_instanced_threaded
(cd "$out" && run timeout 170 "$bin/osgactorbench" --actors=1000,16000 --threads="$threads" \
    --benchmark_filter='^(update|update_cull)/(osgActor_all|osgActor_all_instanced|osgActor_idle|osgActor_idle_instanced|osgAnimation|plainOSG)/1000$|^parallel/')
mkdir -p "$out/cull-sweep"
(cd "$out" && run env OSGACTOR_BENCH_OUT="$out/cull-sweep" timeout 90 "$bin/osgactorbench" --actors=1000 --threads="$threads" \
    --benchmark_filter='^(parallel_cull|parallel_cull_instanced)/' --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true)
run timeout 30 "$bin/osgactor_skin_bench" --benchmark_filter='lbs_k4_pn/262144|frame/'
(cd "$out/images" && tar cf "$out/images.tar" .) && rm -r "$out/images"
