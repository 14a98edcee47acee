#!/usr/bin/env bash
# bench_mc.sh [LVSIM] [N] - Monte Carlo campaign throughput (issue 16) on examples/dof3-branch,
# measured as a user runs it: the whole `lvsim mc` process (load, runs, database; no
# statistics), wall clock, with 1 and 2 threads and with `mpirun -np 2` (when lvsim has MPI),
# beside 1 / (single-run time): the single-run time is the 1-thread campaign's CPU time per
# run (process user + system time / N), so "linear" is what a core gives when it does nothing
# but runs. Scaling = missions/s / (cores x 1 / single-run time). Targets: >= 90 % of linear
# per core, >= 500 missions/s on 2 cores (issue 16), >= 1500 (issue 24). The machine's load
# (uptime) is printed: other work on the cores lowers every wall-clock figure. Instructions per
# mission (exact, whatever the load): valgrind --tool=callgrind lvsim mc ... -n 200 -j 1.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
lvsim="${1:-$here/build/lvsim}"
n="${2:-4000}"
mission="$here/examples/dof3-branch/mission.yaml"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
extra=()
[ "$(id -u)" -eq 0 ] && extra+=(--allow-run-as-root)

# run LABEL CMD...: prints wall seconds and CPU seconds (user + sys of the process tree)
measure() {
  local out="$work/time.$1"; shift
  /usr/bin/env time -f "%e %U %S" -o "$out" "$@" >/dev/null 2>&1
  read -r wall usr sys < "$out"
  echo "$wall $(echo "$usr + $sys" | bc -l)"
}

echo "# lvsim mc throughput: examples/dof3-branch (3 phases, 2 branches), N = $n runs, $(nproc) cores"
echo "# load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
read -r w1 c1 < <(measure j1 "$lvsim" mc "$mission" -n "$n" -j 1 -o "$work/j1" --no-stats)
t_run=$(echo "$c1 / $n" | bc -l)
lin1=$(echo "1 / $t_run" | bc -l)
printf "%-14s %10s %10s %12s %9s\n" "mode" "wall [s]" "runs/s" "linear [/s]" "scaling"
row() { # label wall cores
  local r lin
  r=$(echo "$n / $2" | bc -l)
  lin=$(echo "$3 * $lin1" | bc -l)
  printf "%-14s %10.2f %10.1f %12.1f %8.1f%%\n" "$1" "$2" "$r" "$lin" "$(echo "100 * $r / $lin" | bc -l)"
}
row "-j 1" "$w1" 1
read -r w2 c2 < <(measure j2 "$lvsim" mc "$mission" -n "$n" -j 2 -o "$work/j2" --no-stats)
row "-j 2" "$w2" 2
if command -v mpirun >/dev/null && nm -D "$lvsim" 2>/dev/null | grep -q MPI_Init; then
  read -r w3 c3 < <(measure np2 mpirun "${extra[@]}" --oversubscribe -np 2 "$lvsim" mc "$mission" \
    -n "$n" -j 1 -o "$work/np2" --no-stats)
  row "mpirun -np 2" "$w3" 2
fi
printf "# single-run time (CPU of the -j 1 campaign / N): %.3f ms; 1 / that = %.1f missions/s per core\n" \
  "$(echo "1000 * $t_run" | bc -l)" "$lin1"
echo "# load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
