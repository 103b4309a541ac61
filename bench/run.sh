#!/usr/bin/env bash
# Run every benchmark program of the build and print their tables.
# Usage: bench/run.sh [build-dir]   (reads the models from ../shared/data)
set -euo pipefail
build=${1:-build}
echo "machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "date: $(date -u +%Y-%m-%d)"
# The programs are outside the default build: build them (or bring them up to date) first.
cmake --build "$build" --target bench_programs -j"$(nproc)" >/dev/null
for b in "$build"/bench/bench_*; do
  [[ -x "$b" ]] || continue
  echo
  echo "== $(basename "$b")"
  "$b"
done
