#!/usr/bin/env bash
# Instructions per time step of a benchmark, counted by callgrind (deterministic, unlike wall time
# on a shared host): (I(steps) - I(0 steps)) / steps, so the set-up and the consistent start drop
# out. Usage: instructions_per_step.sh BENCH STEPS [ARGS...], e.g.
#   tests/benchmarks/instructions_per_step.sh build/tests/benchmarks/bench_ale_tether 60 -only ale
# Prints one JSON line. Needs valgrind; takes about a minute per 10^4-element run.
set -euo pipefail
bench=$1 steps=$2
shift 2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
count() {  # total instructions of one run
  valgrind --tool=callgrind --callgrind-out-file="$tmp/out" "$bench" "$@" > /dev/null 2>&1
  callgrind_annotate "$tmp/out" 2> /dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}'
}
i0=$(count "$@" -steps 0)
i1=$(count "$@" -steps "$steps")
echo "{\"bench\": \"$(basename "$bench")\", \"args\": \"$*\", \"steps\": $steps, \"instructions_per_step\": $(( (i1 - i0) / steps ))}"
