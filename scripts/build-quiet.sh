#!/usr/bin/env bash
# build-quiet.sh BUILD_DIR JOBS [CMAKE_FLAGS...] - configure and build lvsim with one line of
# output: the compiler's lines go to BUILD_DIR/build.log, shown (its end) only when the build
# fails. Used by `make demo`, whose output should be the demo's own.
set -uo pipefail
build="${1:-build}"; jobs="${2:-2}"; shift 2 || true
mkdir -p "$build"
log="$build/build.log"
t0=$SECONDS
printf 'building lvsim in %s/ (log: %s) ... ' "$build" "$log"
(
  if [ ! -f "$build/CMakeCache.txt" ]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo "$@" || exit 1
  fi
  cmake --build "$build" -j "$jobs" || exit 1
) > "$log" 2>&1
rc=$?
if [ "$rc" -ne 0 ]; then
  echo "FAILED"
  echo "---- the end of $log ----"
  tail -n 40 "$log"
  exit 1
fi
echo "done in $((SECONDS - t0)) s"
