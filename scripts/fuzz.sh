#!/usr/bin/env bash
# Runs firmament's cargo-fuzz targets (fuzz/), one at a time, each for SECONDS (default 60):
#
#   scripts/fuzz.sh [SECONDS] [TARGET...]      # no TARGET: every target
#
# Targets: scene_toml scene_set obj gltf glb texture date_time (crates/firmament-fuzz/src/lib.rs
# says what each feeds where). Installs cargo-fuzz when it is missing (`cargo install cargo-fuzz
# --locked`); uses the nightly toolchain when rustup has one, else stable with RUSTC_BOOTSTRAP=1
# (cargo-fuzz needs -Z flags: sanitizer and coverage instrumentation).
#
# Each target's corpus is fuzz/corpus/TARGET (kept between runs, git-ignored), seeded from
# crates/firmament-fuzz/seeds/TARGET, its regressions and, for the scene targets, the presets.
# A crash, panic, timeout (-timeout, default 10 s an input) or out-of-memory (-rss_limit_mb,
# default 2048) leaves its input in fuzz/artifacts/TARGET/ and makes the script exit 1 once every
# target has run; copy it to crates/firmament-fuzz/regressions/TARGET/ with the fix.
#
# Environment: FUZZ_ARGS adds libFuzzer options (e.g. FUZZ_ARGS="-max_len=65536"); FUZZ_LOGS is
# the folder of the logs (default fuzz/logs); FUZZ_TOOLCHAIN=stable uses stable even where a
# nightly is installed. One fuzzing process at a time (no -jobs/-fork): the
# machines this runs on have 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-60}"
if ! [[ "$seconds" =~ ^[0-9]+$ ]]; then
    echo "usage: scripts/fuzz.sh [SECONDS] [TARGET...]" >&2
    exit 2
fi
shift || true
all_targets=(scene_toml scene_set obj gltf glb texture date_time)
if [ "$#" -gt 0 ]; then
    targets=("$@")
else
    targets=("${all_targets[@]}")
fi
for target in "${targets[@]}"; do
    if [ ! -f "fuzz/fuzz_targets/$target.rs" ]; then
        echo "fuzz.sh: no target \`$target\`; targets are: ${all_targets[*]}" >&2
        exit 2
    fi
done

if ! cargo fuzz --version >/dev/null 2>&1; then
    echo "fuzz.sh: installing cargo-fuzz" >&2
    cargo install cargo-fuzz --locked
fi

# FUZZ_TOOLCHAIN=stable forces the stable path (to check it where a nightly is installed).
if [ "${FUZZ_TOOLCHAIN:-}" != "stable" ] && command -v rustup >/dev/null 2>&1 &&
    rustup toolchain list | grep -q '^nightly'; then
    fuzz=(cargo +nightly fuzz)
    toolchain="nightly: $(rustc +nightly --version)"
else
    # Stable's rustc takes nightly-only flags with RUSTC_BOOTSTRAP=1; its standard library ships
    # the AddressSanitizer runtime that cargo-fuzz's default sanitizer needs.
    export RUSTC_BOOTSTRAP=1
    fuzz=(cargo fuzz)
    toolchain="RUSTC_BOOTSTRAP=1: $(rustc --version)"
fi
echo "fuzz.sh: $toolchain; ${seconds}s for each of: ${targets[*]}" >&2

logs="${FUZZ_LOGS:-fuzz/logs}"
mkdir -p "$logs"

# Seed the corpora (files already there are kept: the corpus grows from run to run).
for target in "${targets[@]}"; do
    corpus="fuzz/corpus/$target"
    mkdir -p "$corpus"
    for dir in "crates/firmament-fuzz/seeds/$target" "crates/firmament-fuzz/regressions/$target"; do
        if [ -d "$dir" ]; then
            for file in "$dir"/*; do
                copy="$corpus/seed-$(basename "$file")"
                if [ -f "$file" ] && [ ! -e "$copy" ]; then cp "$file" "$copy"; fi
            done
        fi
    done
    case "$target" in
        scene_toml)
            for file in crates/firmament-scene/src/presets/*.toml; do
                copy="$corpus/preset-$(basename "$file")"
                if [ ! -e "$copy" ]; then cp "$file" "$copy"; fi
            done
            ;;
        scene_set)
            for file in crates/firmament-scene/src/presets/*.toml; do
                name="$(basename "$file" .toml)"
                if [ ! -e "$corpus/preset-$name" ]; then printf '%s' "$name" >"$corpus/preset-$name"; fi
            done
            ;;
    esac
done

# Build the targets first, so that the time given is spent fuzzing.
if [ "${#targets[@]}" -eq "${#all_targets[@]}" ]; then
    "${fuzz[@]}" build
else
    for target in "${targets[@]}"; do
        "${fuzz[@]}" build "$target"
    done
fi

failed=()
summary=()
for target in "${targets[@]}"; do
    log="$logs/$target.log"
    echo "fuzz.sh: $target for ${seconds}s (log: $log)" >&2
    start=$(date +%s)
    # shellcheck disable=SC2086 # FUZZ_ARGS is a list of options
    if "${fuzz[@]}" run "$target" "fuzz/corpus/$target" -- \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 ${FUZZ_ARGS:-} \
        >"$log" 2>&1; then
        status="clean"
    else
        status="FAILED (see $log and fuzz/artifacts/$target/)"
        failed+=("$target")
    fi
    wall=$(($(date +%s) - start))
    runs=$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | tail -n 1 || true)
    execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n 1 || true)
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -n 1 || true)
    line="$target: $status; ${wall}s wall; ${execs:-?} executions (${runs:-no final stats}); ${cov:-cov: ?}; corpus $(find "fuzz/corpus/$target" -type f | wc -l) files"
    summary+=("$line")
    echo "fuzz.sh: $line" >&2
done

echo
echo "fuzz.sh summary (${seconds}s each, $toolchain):"
printf '  %s\n' "${summary[@]}"
if [ "${#failed[@]}" -gt 0 ]; then
    echo "fuzz.sh: failures in: ${failed[*]}" >&2
    exit 1
fi
