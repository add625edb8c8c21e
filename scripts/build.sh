#!/usr/bin/env bash
# Builds quietly: one progress line instead of the compiler's lines, which go to BUILD_DIR/build.log;
# on failure, the errors and the end of that log. Used by the Makefile.
# Usage: scripts/build.sh BUILD_DIR JOBS [TARGET]   (no TARGET: everything)
set -uo pipefail

dir=$1
jobs=$2
target=${3:-}
what=${target:-everything}
log=$dir/build.log
args=(--build "$dir" -j"$jobs")
[ -n "$target" ] && args+=(--target "$target")
tty=0
[ -t 1 ] && tty=1

start=$(date +%s)
# CMake's Makefiles print "[ 42%] Building …", Ninja "[12/60] Building …": the share of the way
# shown on a terminal as one line rewritten in place, in a log as one line per tenth of the way.
cmake "${args[@]}" 2>&1 | tee "$log" | awk -v tty="$tty" -v what="$what" '
  function show(p) {
    if (tty) { printf "\r  building %s: %3d%%", what, p; fflush() }
    else if (int(p / 10) > shown) { shown = int(p / 10); printf "  building %s: %d%%\n", what, p; fflush() }
  }
  match($0, /^\[ *[0-9]+%\]/) { show(substr($0, RSTART + 1, RLENGTH - 3) + 0) }
  match($0, /^\[[0-9]+\/[0-9]+\]/) { split(substr($0, 2, RLENGTH - 2), n, "/"); show(int(100 * n[1] / n[2])) }
  END { if (tty) printf "\r\033[K" }'
status=${PIPESTATUS[0]}
seconds=$(( $(date +%s) - start ))
if [ "$status" -ne 0 ]; then
  echo "build of $what FAILED after ${seconds} s; errors (whole output: $log):" >&2
  grep -E -A3 "error|Error" "$log" | head -60 >&2
  exit "$status"
fi
printf '  built %s in %d min %02d s (compiler output: %s)\n' "$what" $((seconds / 60)) $((seconds % 60)) "$log"
