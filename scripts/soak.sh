#!/usr/bin/env bash
# The viewer's soak test (issue 10): `firmament view` driven by --frames for a long run with the
# clock running (not --paused), on a virtual X display, its resident memory (VmRSS) sampled from
# /proc every few seconds into a CSV; at the end, the start, peak and end figures.
#
#   scripts/soak.sh [FRAMES]        # default 20000
#
# Environment:
#   FIRMAMENT     the binary (default target/release/firmament; build it with
#                 `cargo build --release -p firmament`)
#   PRESET        the scene (default earth-sunset); SIZE the window (default 64x36)
#   INTERVAL      seconds between samples (default 2)
#   CSV           where the samples go (default soak-<FRAMES>.csv in the working directory)
#   EXTRA         more arguments for `firmament view` (e.g. "--backend vulkan")
#
# "Start" is the first sample after the window's first frames (the GPU set up, the pipelines
# built); growth is judged from there to the end. Linux only (/proc); needs Xvfb (scripts/setup.sh
# installs it).
set -euo pipefail

frames="${1:-20000}"
root="$(cd "$(dirname "$0")/.." && pwd)"
bin="${FIRMAMENT:-$root/target/release/firmament}"
preset="${PRESET:-earth-sunset}"
size="${SIZE:-64x36}"
interval="${INTERVAL:-2}"
csv="${CSV:-soak-$frames.csv}"

if [ ! -x "$bin" ]; then
  echo "soak: no binary at $bin: run \`cargo build --release -p firmament\` first (or set FIRMAMENT)" >&2
  exit 1
fi
if ! command -v Xvfb >/dev/null; then
  echo "soak: Xvfb is missing: run scripts/setup.sh (Debian/Ubuntu: apt-get install xvfb)" >&2
  exit 1
fi

# A free display number.
display=""
for n in $(seq 300 399); do
  if [ ! -e "/tmp/.X11-unix/X$n" ] && [ ! -e "/tmp/.X$n-lock" ]; then
    display=":$n"
    break
  fi
done
if [ -z "$display" ]; then
  echo "soak: no free X display in :300 to :399" >&2
  exit 1
fi

xvfb_pid=""
view_pid=""
cleanup() {
  if [ -n "$view_pid" ]; then kill "$view_pid" 2>/dev/null || true; fi
  if [ -n "$xvfb_pid" ]; then kill "$xvfb_pid" 2>/dev/null || true; fi
}
trap cleanup EXIT

Xvfb "$display" -screen 0 640x480x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
for _ in $(seq 1 200); do
  [ -e "/tmp/.X11-unix/X${display#:}" ] && break
  sleep 0.05
done

log="${csv%.csv}.log"
started=$(date +%s.%N)
# shellcheck disable=SC2086
DISPLAY="$display" "$bin" view --preset "$preset" --size "$size" --frames "$frames" ${EXTRA:-} \
  2>"$log" &
view_pid=$!

echo "seconds,rss_kib" >"$csv"
echo "soak: firmament view --preset $preset --size $size --frames $frames (pid $view_pid, display $display)," \
  "sampling VmRSS every ${interval} s into $csv"
while kill -0 "$view_pid" 2>/dev/null; do
  rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$view_pid/status" 2>/dev/null || true)
  if [ -n "$rss" ]; then
    now=$(date +%s.%N)
    awk -v a="$now" -v b="$started" -v r="$rss" 'BEGIN { printf "%.1f,%s\n", a - b, r }' >>"$csv"
  fi
  sleep "$interval"
done
status=0
wait "$view_pid" || status=$?
view_pid=""
ended=$(date +%s.%N)
seconds=$(awk -v a="$ended" -v b="$started" 'BEGIN { printf "%.1f", a - b }')

if [ "$status" -ne 0 ]; then
  echo "soak: the viewer exited with status $status:" >&2
  tail -n 20 "$log" >&2
  exit "$status"
fi

# Start: the third sample (after set-up); peak and end over the run.
awk -F, -v frames="$frames" -v seconds="$seconds" '
  NR == 1 { next }
  { n++; rss[n] = $2; t[n] = $1; if ($2 > peak) { peak = $2; peak_t = $1 } }
  END {
    if (n == 0) { print "soak: no samples (the run was shorter than one interval)"; exit 1 }
    s = (n >= 3) ? 3 : 1
    printf "frames %d in %.1f s (%.0f frames/s), %d samples\n", frames, seconds, frames / seconds, n
    printf "RSS start %.1f MiB (at %.1f s), peak %.1f MiB (at %.1f s), end %.1f MiB (at %.1f s)\n",
      rss[s] / 1024, t[s], peak / 1024, peak_t, rss[n] / 1024, t[n]
    printf "growth from start to end: %+.1f MiB (%+.2f %%)\n", (rss[n] - rss[s]) / 1024,
      100 * (rss[n] - rss[s]) / rss[s]
  }' "$csv"
grep -E "viewer: " "$log" | tail -n 1 || true
