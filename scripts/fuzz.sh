#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/: clang, -fsanitize=fuzzer,address,undefined) in the AddressSanitizer build
# (build-asan/, shared with scripts/test-sanitizers.sh asan: after it, nothing is left to build) and runs each.
#
#   scripts/fuzz.sh          the short run (CI, scripts/test.sh): each target for OSGACTOR_FUZZ_SECONDS on one core,
#                            OSGACTOR_FUZZ_JOBS targets at a time (default: every core), starting from its committed
#                            corpus (fuzz/corpus/<target>/), the project's data and the saved findings, copied into a
#                            temporary folder: nothing is written to the repository.
#   scripts/fuzz.sh --long   the long run, for a many-core machine and hours: each target in turn with -fork across
#                            OSGACTOR_FUZZ_JOBS processes (default: every core) for OSGACTOR_FUZZ_SECONDS (default
#                            3600), on a working corpus kept between runs ($build/fuzz-work/<target>/); then the
#                            corpus is minimised (-merge=1) into fuzz/corpus/<target>/ and the run's figures
#                            (executions, coverage, findings) are added to fuzz/corpus/runs.tsv. Commit both.
#   scripts/fuzz.sh --merge  only the minimising step, from the working corpus of earlier long runs.
#   scripts/fuzz.sh --coverage  the edges each target reaches in the parsers' sources (osgActor/io, mocap, text),
#                            running its committed corpus and seeds once (docs/robustness.md quotes the figures).
#
# Fails on any crash, hang, leak, sanitizer report or broken parser contract (fuzz/ParserContract: what a reader
# accepts is written, read back and compared); the input is kept in $OSGACTOR_FUZZ_ARTIFACTS
# (build-asan/fuzz-artifacts/), to be added to tests/robustness/inputs/<parser>/ once fixed (docs/robustness.md).
#   OSGACTOR_FUZZ_SECONDS  seconds per target (default 60 short, 3600 long)
#   OSGACTOR_FUZZ_TARGETS  which targets (default: all of them)
#   OSGACTOR_FUZZ_JOBS     short run: targets fuzzed at once; long run: parallel fuzzing processes per target
#                          (default: nproc)
#   OSGACTOR_ASAN_BUILD_DIR, OSGACTOR_JOBS
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mode=short
case "${1:-}" in
    --long) mode=long ;;
    --merge) mode=merge ;;
    --coverage) mode=coverage ;;
    "") ;;
    *) echo "usage: scripts/fuzz.sh [--long | --merge | --coverage]" >&2; exit 2 ;;
esac
build="${OSGACTOR_ASAN_BUILD_DIR:-$root/build-asan}"
default_seconds=60
[ "$mode" = long ] && default_seconds=3600
seconds="${OSGACTOR_FUZZ_SECONDS:-$default_seconds}"
fuzz_jobs="${OSGACTOR_FUZZ_JOBS:-$(nproc)}"
targets=(${OSGACTOR_FUZZ_TARGETS:-actor bvh asf amc trajectory_csv gltf rigged})
mocap="$root/data/mocap"
assimp=/usr/share/assimp/models/BVH
gltf2=/usr/share/assimp/models/glTF2
artifacts="${OSGACTOR_FUZZ_ARTIFACTS:-$build/fuzz-artifacts}"
committed="$root/fuzz/corpus"
# Inputs are cut to their first 64 KiB (a mocap file's header and first frames, where the parsing decisions are),
# which keeps each execution fast. The committed corpus keeps no file longer than 16 KiB, to stay small in the
# repository: the long inputs are mostly the real mocap files cut short, which every run adds as seeds anyway.
max_len=65536
max_committed=16384

source "$root/scripts/sanitizers/configure.sh"
sanitizer_configure asan "$build"
cmake --build "$build" -j "${OSGACTOR_JOBS:-$(nproc)}" --target $(printf 'fuzz_%s ' "${targets[@]}")

# Seeds per target besides the committed corpus: shell globs, those that match nothing are skipped.
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

# copy_seeds <target> <folder>: the target's committed corpus and seeds into folder.
copy_seeds() {
    local target="$1" folder="$2" seeds="seeds_${1}[@]" seed
    mkdir -p "$folder"
    for seed in "$committed/$target"/* "${!seeds}"; do
        [ -f "$seed" ] && cp "$seed" "$folder/"
    done
    return 0
}

# fuzz_options <target>: what every run of the target is given.
fuzz_options() {
    local dict="$root/fuzz/$1.dict"
    [ -f "$dict" ] && echo "-dict=$dict"
    # -timeout: an input that takes longer than 10 s is a hang. -rss_limit_mb: a runaway allocation is a finding.
    echo "-timeout=10 -rss_limit_mb=2048 -max_len=$max_len -artifact_prefix=$artifacts/$1-"
}

# The last status line of a libFuzzer log: "#<executions> ... cov: <edges> ft: <features> corp: <n>/<size> ...".
status_of() { grep -E '^#[0-9]+' "$1" | tail -n 1 || true; }
executions_of() { sed -nE 's/^#([0-9]+).*/\1/p' <<<"$1"; }
field_of() { sed -nE "s/.* $2: ([0-9]+).*/\1/p" <<<"$1"; }

# merge <target>: minimises the working corpus (and what is committed) into fuzz/corpus/<target>/.
merge() {
    local target="$1" fresh="$work/$1.merged"
    mkdir -p "$fresh" "$committed/$target"
    if ! "$build/bin/fuzz_$target" -merge=1 $(fuzz_options "$target") "$fresh" "$committed/$target" \
            "$build/fuzz-work/$target" >"$work/$target.merge.log" 2>&1; then
        tail -n 30 "$work/$target.merge.log"
        return 1
    fi
    rm -rf "$committed/$target"
    mkdir -p "$committed/$target"
    find "$fresh" -type f -size -$((max_committed + 1))c -exec cp {} "$committed/$target/" \;
    echo "fuzz: $target: fuzz/corpus/$target/ holds $(ls "$committed/$target" | wc -l) inputs" \
         "($(du -sk "$committed/$target" | cut -f1) KiB)"
}

# coverage <target>: "file covered/total" edges, per source file of the parsers, from -print_coverage's functions.
coverage() {
    local target="$1" corpus="$work/$1.coverage"
    copy_seeds "$target" "$corpus"
    "$build/bin/fuzz_$target" $(fuzz_options "$target") -runs=0 -print_coverage=1 "$corpus" 2>&1 |
        awk -v target="$target" '
            /^(UN)?COVERED_FUNC:/ {
                split($5, e, "/"); file = $NF; sub(/:[0-9]+$/, "", file)
                if (file !~ /osgActor\/(io|mocap|text)\/[A-Za-z]+\.cpp$/) next
                sub(/.*osgActor\//, "", file); covered[file] += e[1]; total[file] += e[2]
            }
            END { for (f in total) if (covered[f] > 0)
                      printf "fuzz: %s: %s %d/%d edges (%.0f%%)\n", target, f, covered[f], total[f],
                             100 * covered[f] / total[f] }' | sort
}

# One target's short run, on one core: what it says goes to $work/<target>.said, and the file $work/<target>.failed
# is made if it failed.
fuzz_short() {
    local target="$1" corpus="$work/$1" log="$work/$1.log"
    copy_seeds "$target" "$corpus"
    {
        echo "fuzz: $target for ${seconds}s on $(ls "$corpus" | wc -l) inputs"
        if ! "$build/bin/fuzz_$target" $(fuzz_options "$target") -max_total_time="$seconds" -print_final_stats=1 \
                "$corpus" >"$log" 2>&1; then
            tail -n 60 "$log"
            touch "$work/$target.failed"
        else
            grep -E '^stat::(number_of_executed_units|new_units_added)' "$log" | tr '\n' ' '
            echo
        fi
    } >"$work/$target.said" 2>&1
}

failed=()
if [ "$mode" = short ]; then
    # The targets side by side, OSGACTOR_FUZZ_JOBS at a time: each still fuzzes for its seconds on one core.
    echo "fuzz: ${#targets[@]} targets, ${seconds}s each, $fuzz_jobs at a time"
    running=0
    for target in "${targets[@]}"; do
        if [ "$running" -ge "$fuzz_jobs" ]; then
            wait -n
            running=$((running - 1))
        fi
        fuzz_short "$target" &
        running=$((running + 1))
    done
    wait
    for target in "${targets[@]}"; do
        cat "$work/$target.said"
        [ ! -e "$work/$target.failed" ] || failed+=("$target")
    done
fi
for target in "${targets[@]}"; do
    log="$work/$target.log"
    case "$mode" in
    short) ;;
    long)
        corpus="$build/fuzz-work/$target"
        copy_seeds "$target" "$corpus"
        echo "fuzz: $target for ${seconds}s, $fuzz_jobs processes, on $(ls "$corpus" | wc -l) inputs" \
             "(log: $build/fuzz-work/$target.log)"
        status=0
        # -fork: each process fuzzes a share of the corpus for a while, then its new inputs join the corpus;
        # -ignore_crashes=0: the first finding stops the run (it is in $artifacts).
        "$build/bin/fuzz_$target" $(fuzz_options "$target") -max_total_time="$seconds" -fork="$fuzz_jobs" \
            -ignore_crashes=0 -ignore_timeouts=0 -ignore_ooms=0 "$corpus" >"$build/fuzz-work/$target.log" 2>&1 ||
            status=$?
        last="$(status_of "$build/fuzz-work/$target.log")"
        findings="$(ls "$artifacts" | grep -c "^$target-" || true)"
        echo "fuzz: $target: $last"
        if [ "$status" -ne 0 ]; then
            tail -n 60 "$build/fuzz-work/$target.log"
            failed+=("$target")
        fi
        merge "$target" || failed+=("$target")
        [ -f "$committed/runs.tsv" ] ||
            printf 'date\ttarget\tseconds\tprocesses\texecutions\tcoverage\tfeatures\tcorpus\tfindings\n' \
                >"$committed/runs.tsv"
        printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%Y-%m-%d)" "$target" "$seconds" "$fuzz_jobs" \
            "$(executions_of "$last")" \
            "$(field_of "$last" cov)" "$(field_of "$last" ft)" "$(ls "$committed/$target" | wc -l)" "$findings" \
            >>"$committed/runs.tsv"
        ;;
    merge)
        merge "$target" || failed+=("$target")
        ;;
    coverage)
        coverage "$target"
        ;;
    esac
done
if [ ${#failed[@]} -ne 0 ]; then
    echo "fuzz: FAILED: ${failed[*]} (inputs in $artifacts)" >&2
    exit 1
fi
case "$mode" in
    short) echo "fuzz: ${#targets[@]} targets, ${seconds}s each, no findings" ;;
    long) echo "fuzz: ${#targets[@]} targets, ${seconds}s each on $fuzz_jobs processes, no findings;" \
               "fuzz/corpus/ refreshed, figures in fuzz/corpus/runs.tsv" ;;
    merge) echo "fuzz: fuzz/corpus/ refreshed from $build/fuzz-work/" ;;
    coverage) ;;
esac
