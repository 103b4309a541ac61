#!/usr/bin/env bash
# Time of selective padding's plan (mapping analysis + binary problem, thesis §4.3–4.4) on the
# hex meshes of `polycube run` outputs, median of several runs, as a markdown table: #H, |HF|,
# |PF|, the program's size, how it was solved (an integral LP relaxation or branch and cut),
# proven optimal or the gap, and the seconds. The layer is inserted but not optimized.
# Usage: bench/plan.sh [--build DIR] RUN_OUTPUT...
#   RUN_OUTPUT: a folder `polycube run` wrote (report.json, hex_optimized.mesh, hex.mesh)
#   env: REPEAT=3 (runs per mesh), ANALYSIS=gridded (analyse the gridded hex.mesh, where the
#   map's distortion is still visible, instead of the optimized mesh), TIME_LIMIT (seconds for the
#   binary problem; default the tool's).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
build=$root/build
if [[ "${1:-}" == --build ]]; then build=$(cd "$2" && pwd); shift 2; fi
pc=$build/polycube
[[ -x "$pc" ]] || { echo "bench/plan.sh: $pc not found; run make first" >&2; exit 2; }
[[ $# -gt 0 ]] || { echo "usage: bench/plan.sh [--build DIR] RUN_OUTPUT..." >&2; exit 1; }
repeat=${REPEAT:-3}
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

reports=()
for dir in "$@"; do
  [[ -f "$dir/report.json" && -f "$dir/hex_optimized.mesh" ]] || { echo "== $dir: not a run output, skipped" >&2; continue; }
  input=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["input"])' "$dir/report.json")
  extra=()
  [[ "${ANALYSIS:-}" == gridded ]] && extra+=(--analysis-mesh "$dir/hex.mesh")
  [[ -n "${TIME_LIMIT:-}" ]] && extra+=(--time-limit "$TIME_LIMIT")
  key=$(basename "$dir")
  for ((i = 1; i <= repeat; ++i)); do
    echo "== $key, run $i of $repeat" >&2
    "$pc" -q pad "$dir/hex_optimized.mesh" --target "$input" --selective --no-optimize --keep-failed \
      -o "$scratch/padded.mesh" --report "$scratch/${key}_$i.json" "${extra[@]+"${extra[@]}"}" > /dev/null 2>&1
    reports+=("$scratch/${key}_$i.json")
  done
done

python3 - "${reports[@]}" <<'PY'
import json, statistics, sys, collections
runs = collections.OrderedDict()
for path in sys.argv[1:]:
    key = path.rsplit("/", 1)[1].rsplit("_", 1)[0]
    try:
        runs.setdefault(key, []).append(json.load(open(path)))
    except (OSError, ValueError):
        runs.setdefault(key, [])
print("| mesh | #H | \\|HF\\| | \\|PF\\| | variables | rows | solved by | optimal (gap) | plan s (median) | min–max |")
print("|---|---:|---:|---:|---:|---:|---|---|---:|---|")
for key, js in runs.items():
    if not js:
        print(f"| {key} | failed | | | | | | | | |")
        continue
    t = [j["analysis"]["seconds"] + j.get("selection", {}).get("seconds", 0) for j in js]
    j = js[0]
    a, s = j["analysis"], j.get("selection", {})
    if a["hard_facets"] == 0:  # nothing to pad: no program
        print(f"| {key} | | 0 | 0 | | | nothing to pad | | {statistics.median(t):.2f} | {min(t):.2f}–{max(t):.2f} |")
        continue
    opt = "yes" if s["optimal"] else f"no ({100 * s['gap']:.2f} %)"
    print(f"| {key} | {j['before']['hexes']:,} | {a['hard_facets']:,} | {s['selected_facets']:,} | {s['variables']:,} | "
          f"{s['rows']:,} | {s.get('solver', '')} | {opt} | {statistics.median(t):.2f} | {min(t):.2f}–{max(t):.2f} |")
PY
