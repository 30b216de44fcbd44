#!/bin/sh
# The measurements that need a machine with a GPU and many cores (docs/performance.md, "GPU and many-core
# figures"), in one go, from a build made with scripts/build.sh:
#   1. the whole frame drawn on the GPU (osgactor_gpu_draw_bench: EGL, no display needed), rigid and skinned crowds
#      of 1000 and 10,000 against osgAnimation and plain OSG, and osgActor's GPU skinning against its CPU skinning
#      on that GPU (images);
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

run timeout 240 "$bin/osgactor_gpu_draw_bench" --actors=1000,10000 --seconds=1.5 --images="$out/images" \
    --cesium-man="$root/data/models/CesiumMan/CesiumMan.gltf"
run timeout 110 "$bin/osgactor_gpu_draw_bench" --actors=10000 --seconds=1.5 --threading=draw \
    --systems=rigid_osgActor,rigid_osgActor_group,rigid_osgActor_instanced,skinned_osgActor_gpu,skinned_osgActor_instanced \
    --cesium-man="$root/data/models/CesiumMan/CesiumMan.gltf"
(cd "$out" && run timeout 170 "$bin/osgactorbench" --actors=1000,16000 --threads="$threads" \
    --benchmark_filter='^(update|update_cull)/(osgActor_all|osgActor_idle|osgAnimation|plainOSG)/1000$|^parallel/')
mkdir -p "$out/cull-sweep"
(cd "$out" && run env OSGACTOR_BENCH_OUT="$out/cull-sweep" timeout 90 "$bin/osgactorbench" --actors=1000 --threads="$threads" \
    --benchmark_filter='^(parallel_cull|parallel_cull_instanced)/' --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true)
run timeout 30 "$bin/osgactor_skin_bench" --benchmark_filter='lbs_k4_pn/262144|frame/'
(cd "$out/images" && tar cf "$out/images.tar" .) && rm -r "$out/images"
