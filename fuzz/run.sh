#!/usr/bin/env bash
# Run the mission-parser fuzzer for a bounded time.
#   fuzz/run.sh BINARY [SECONDS] [extra libFuzzer options]
# Seeds: fuzz/corpus (good and bad mission files, read only). New inputs go to
# BINARY's directory (fuzz-corpus/), crashes to fuzz-artifacts/. Exit status: libFuzzer's
# (non-zero on a crash, a leak, a timeout of 5 s per input or more than 2 GB of memory).
set -euo pipefail
bin=$1
secs=${2:-60}
shift $(( $# < 2 ? $# : 2 ))
here=$(cd "$(dirname "$0")" && pwd)
out=$(cd "$(dirname "$bin")" && pwd)
mkdir -p "$out/fuzz-corpus" "$out/fuzz-artifacts"
exec "$bin" -max_total_time="$secs" -rss_limit_mb=2048 -timeout=5 -max_len=8192 \
  -dict="$here/mission.dict" -artifact_prefix="$out/fuzz-artifacts/" -print_final_stats=1 \
  "$@" "$out/fuzz-corpus" "$here/corpus"
