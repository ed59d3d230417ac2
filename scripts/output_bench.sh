#!/usr/bin/env bash
# Times firmament's output side by side for two builds (docs/PERFORMANCE.md, "Pipelined output"):
# a 1920×1080 `earth-noon` time-lapse to PNG and with --exr, and 7680×4320 PNG and EXR stills,
# OLD then NEW, ROUNDS times, each into an empty folder:
#
#   scripts/output_bench.sh OLD_BINARY NEW_BINARY
#
# Environment: BACKEND (default vulkan; gl for llvmpipe), FRAMES (120), LW×LH (1920×1080), SW×SH
# (7680×4320), ROUNDS (2). Each line: the frame loop's time as the command reports it, then the
# whole command's wall, user and sys time and the output's size. Build each binary with
# `cargo build --release -p firmament` (the old one in a `git worktree` at the commit before).
set -uo pipefail
if [[ $# -ne 2 ]]; then
  sed -n '2,11p' "$0" | cut -c3-
  exit 2
fi
declare -A BIN=([old]="$(realpath "$1")" [new]="$(realpath "$2")")
BACKEND=${BACKEND:-vulkan} FRAMES=${FRAMES:-120} LW=${LW:-1920} LH=${LH:-1080}
SW=${SW:-7680} SH=${SH:-4320} ROUNDS=${ROUNDS:-2}
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
TIMEFORMAT='wall %R s, user %U s, sys %S s'
echo "$(nproc) cores; backend $BACKEND"

lapse() { # old|new, extra arguments
  local v=$1
  shift
  rm -rf "$W/l"
  { time "${BIN[$v]}" timelapse --backend "$BACKEND" --preset earth-noon --from 2024-06-21T06:00:00Z \
      --to 2024-06-21T18:00:00Z --frames "$FRAMES" --width "$LW" --height "$LH" -o "$W/l" "$@" 2>&1 \
      | grep -Eo '[0-9]+ frames rendered in [0-9.]+ s \([0-9.]+ frames/s'; } 2>&1 | tr '\n' ' '
  echo "<- timelapse $v $* ($(du -sm "$W/l" | cut -f1) MB)"
}

still() { # old|new, file name
  local v=$1 f=$2
  rm -f "$W/$f"
  { time "${BIN[$v]}" render --backend "$BACKEND" -q --width "$SW" --height "$SH" -o "$W/$f"; } 2>&1 | tr '\n' ' '
  echo "<- ${SW}x$SH still $v $f ($(du -m "$W/$f" | cut -f1) MB)"
}

# One small render first: the driver's shader caches and the page cache warm for both.
"${BIN[new]}" render --backend "$BACKEND" -q --width 64 --height 36 -o "$W/warm.png" || exit 1
for _ in $(seq "$ROUNDS"); do
  for v in old new; do lapse "$v"; done
  for v in old new; do lapse "$v" --exr; done
  for v in old new; do still "$v" x.png; done
  for v in old new; do still "$v" x.exr; done
done
