#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/: clang, -fsanitize=fuzzer,address,undefined) in the AddressSanitizer build
# (build-asan/, shared with scripts/test-sanitizers.sh asan: after it, nothing is left to build) and runs each for a
# bounded time on a corpus seeded from the project's data and the real mocap files (copied into a temporary folder;
# nothing is written to the repository). Fails on any crash, hang, leak or sanitizer report; the input that caused
# it is kept in $OSGACTOR_FUZZ_ARTIFACTS (build-asan/fuzz-artifacts/) to be added to tests/robustness/inputs/.
#   OSGACTOR_FUZZ_SECONDS  seconds per target (default 60)
#   OSGACTOR_FUZZ_TARGETS  which targets (default: all of them)
#   OSGACTOR_ASAN_BUILD_DIR, OSGACTOR_JOBS
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${OSGACTOR_ASAN_BUILD_DIR:-$root/build-asan}"
seconds="${OSGACTOR_FUZZ_SECONDS:-60}"
targets=(${OSGACTOR_FUZZ_TARGETS:-actor bvh asf amc trajectory_csv gltf rigged})
mocap="$root/data/mocap"
assimp=/usr/share/assimp/models/BVH
gltf2=/usr/share/assimp/models/glTF2
artifacts="${OSGACTOR_FUZZ_ARTIFACTS:-$build/fuzz-artifacts}"

source "$root/scripts/sanitizers/configure.sh"
sanitizer_configure asan "$build"
cmake --build "$build" -j "${OSGACTOR_JOBS:-$(nproc)}" --target $(printf 'fuzz_%s ' "${targets[@]}")

# Seeds per target: shell globs, those that match nothing are skipped.
seeds_actor=("$root"/data/*.actor "$root"/fuzz/seeds/actor/* "$root"/tests/robustness/inputs/actor/*)
seeds_bvh=("$mocap"/bvh/*.bvh "$assimp"/*.bvh "$root"/tests/robustness/inputs/bvh/*)
seeds_asf=("$mocap"/asfamc/*.asf "$root"/tests/robustness/inputs/asf/*)
seeds_amc=("$mocap"/asfamc/11_*.amc "$root"/tests/robustness/inputs/amc/*)
seeds_trajectory_csv=("$root"/tests/motion/data/*.csv "$root"/tests/robustness/inputs/trajectory_csv/*)
seeds_gltf=("$gltf2"/*/*.gl[tb]* "$gltf2"/*/*/*.gl[tb]* "$root"/data/models/CesiumMan/*.gltf "$root"/tests/robustness/inputs/gltf/*)
seeds_rigged=("$root"/tests/robustness/inputs/rigged/*)

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$artifacts"
failed=()
for target in "${targets[@]}"; do
    corpus="$work/$target"
    mkdir -p "$corpus"
    seeds="seeds_${target}[@]"
    for seed in "${!seeds}"; do
        [ -f "$seed" ] && cp "$seed" "$corpus/"
    done
    dict=()
    [ -f "$root/fuzz/$target.dict" ] && dict=(-dict="$root/fuzz/$target.dict")
    echo "fuzz: $target for ${seconds}s on $(ls "$corpus" | wc -l) seeds"
    # -max_len: big mocap seeds are cut to their first 64 KiB (header and first frames), which keeps each run fast.
    # -timeout: an input that takes longer than 10 s is a hang. -rss_limit_mb: a runaway allocation is a finding.
    if ! "$build/bin/fuzz_$target" "${dict[@]}" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
            -max_len=65536 -print_final_stats=1 -artifact_prefix="$artifacts/${target}-" "$corpus" \
            >"$work/$target.log" 2>&1; then
        tail -n 60 "$work/$target.log"
        failed+=("$target")
    else
        grep -E '^stat::(number_of_executed_units|new_units_added)' "$work/$target.log" | tr '\n' ' '
        echo
    fi
done
if [ ${#failed[@]} -ne 0 ]; then
    echo "fuzz: FAILED: ${failed[*]} (inputs in $artifacts)" >&2
    exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds}s each, no findings"
