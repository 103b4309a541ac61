#!/usr/bin/env bash
# Run every mesh-reader fuzz target (libFuzzer + AddressSanitizer + UBSan) for N seconds each.
#   scripts/fuzz.sh [seconds] [format ...]     (seconds default 60; formats default: all of
#                                               obj off stl ply mesh vtk msh)
# Builds with clang++ in build-fuzz/ (separate from the normal build), seeds each target with
# the files of tests/data that have its extension, keeps the growing corpus in
# build-fuzz/corpus/<format>/ and writes any crashing input to build-fuzz/artifacts/<format>/.
# Exits non-zero if a target found a crash.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-60}"
shift || true
formats=("$@")
[ ${#formats[@]} -eq 0 ] && formats=(obj off stl ply mesh vtk msh)
build="${POLYCUBE_FUZZ_BUILD_DIR:-$root/build-fuzz}"

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (apt-get install clang)" >&2; exit 1; }
CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DPOLYCUBE_BUILD_FUZZ=ON -DPOLYCUBE_BUILD_TESTS=OFF -DPOLYCUBE_BUILD_BENCH=OFF >/dev/null
targets=()
for f in "${formats[@]}"; do targets+=("fuzz_$f"); done
cmake --build "$build" --target "${targets[@]}" -j"$(nproc)"

status=0
for f in "${formats[@]}"; do
  seeds="$build/seeds/$f"
  corpus="$build/corpus/$f"
  artifacts="$build/artifacts/$f"
  rm -rf "$seeds"
  mkdir -p "$seeds" "$corpus" "$artifacts"
  find "$root/tests/data" -type f -iname "*.$f" -exec cp {} "$seeds/" \;
  echo "== fuzz_$f: ${seconds}s, $(ls "$seeds" | wc -l) seed files"
  if "$build/fuzz/fuzz_$f" "$corpus" "$seeds" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -artifact_prefix="$artifacts/" -print_final_stats=1 >"$build/fuzz_$f.log" 2>&1; then
    echo "   ok: $(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$build/fuzz_$f.log" | grep -o '[0-9]*$') runs, no crash"
  else
    echo "   CRASH: see $build/fuzz_$f.log and $artifacts/" >&2
    status=1
  fi
done
exit $status
