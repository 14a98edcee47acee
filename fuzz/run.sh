#!/usr/bin/env bash
# Run one libFuzzer target for a bounded time.
#   fuzz/run.sh BINARY [SECONDS] [extra libFuzzer options]
# BINARY is build*/fuzz/fuzz_NAME (fuzz/fuzz.cmake); its seeds are fuzz/corpus/NAME (read
# only), its dictionary fuzz/NAME.dict when there is one. New inputs go to NAME-corpus/ beside
# BINARY, crashes to NAME-artifacts/, the target's temporary files to NAME-tmp/. Exit status: libFuzzer's (non-zero on a crash, a leak, a
# timeout of 5 s per input or more than 2 GB of memory).
set -euo pipefail
bin=$1
secs=${2:-60}
shift $(( $# < 2 ? $# : 2 ))
here=$(cd "$(dirname "$0")" && pwd)
out=$(cd "$(dirname "$bin")" && pwd)
name=$(basename "$bin")
name=${name#fuzz_}
opts=(-max_total_time="$secs" -rss_limit_mb=2048 -timeout=5 -print_final_stats=1
      -artifact_prefix="$out/$name-artifacts/")
[ -f "$here/$name.dict" ] && opts+=(-dict="$here/$name.dict")
case $name in
  mission|tables) opts+=(-max_len=8192) ;;
  results) opts+=(-max_len=24576) ;;
  fmu) opts+=(-max_len=2048 -close_fd_mask=3) ;; # stderr: the FMU's refusals of freed instances
  cli) opts+=(-max_len=1024 -close_fd_mask=3) ;; # the commands' own output
esac
# the targets' private folders under NAME-tmp/ (TMPDIR), emptied at every start: a run that
# ends by its time limit or a crash leaves its folder behind (libFuzzer exits without atexit)
rm -rf "$out/$name-tmp"
mkdir -p "$out/$name-corpus" "$out/$name-artifacts" "$out/$name-tmp"
export TMPDIR="$out/$name-tmp"
exec "$out/$(basename "$bin")" "${opts[@]}" "$@" "$out/$name-corpus" "$here/corpus/$name"
