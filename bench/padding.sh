#!/usr/bin/env bash
# Padding (`polycube pad`) of every optimized hex mesh bench/chain.sh left in OUT, with the input
# surface as target; prints the table of thesis Table 4.1 (markdown): #H, #Sv, #Se, mSJ, aSJ
# without and with padding, and the time of each step.
# Usage: bench/padding.sh [--table-only] [build-dir]
#   env: OUT=out/bench (chain.sh's output), ONLY="surface/bunny tet/cup ..." pads just those,
#   MODE=global|selective (default global), ANALYSIS=gridded: selective padding analyses the
#   gridded hex.mesh instead of the optimized mesh, LAMBDA (selective's λ, default the tool's).
# After MODE=global and MODE=selective runs, bench/table41.py OUT puts both beside the unpadded
# meshes (thesis Table 4.1).
set -uo pipefail
table_only=0
[[ "${1:-}" == --table-only ]] && { table_only=1; shift; }
build=${1:-build}
mode=${MODE:-global}
extra=()
[[ "$mode" == selective ]] && extra+=(--selective)
[[ -n "${LAMBDA:-}" ]] && extra+=(--lambda "$LAMBDA")
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
out=${OUT:-$root/out/bench}
if [[ "$build" = /* ]]; then pc=$build/polycube; else pc=$root/$build/polycube; fi
[[ -x "$pc" ]] || { echo "bench/padding.sh: $pc not found; run make first" >&2; exit 2; }

for rep in "$out"/*/report.json; do
  [[ $table_only -eq 1 ]] && break
  dir=$(dirname "$rep"); key=$(basename "$dir"); kind=${key%%_*}; name=${key#*_}
  if [[ -n "${ONLY:-}" && " $ONLY " != *" $kind/$name "* ]]; then continue; fi
  [[ -f "$dir/hex_optimized.mesh" ]] || { echo "== $kind/$name: no hex_optimized.mesh, skipped" >&2; continue; }
  input=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["input"])' "$rep")
  echo "== $kind/$name" >&2
  analysis=()
  [[ "$mode" == selective && "${ANALYSIS:-}" == gridded ]] && analysis=(--analysis-mesh "$dir/hex.mesh")
  "$pc" -q pad "$dir/hex_optimized.mesh" --target "$input" -o "$dir/hex_$mode.mesh" --vtk "$dir/hex_$mode.vtk" \
    --report "$dir/pad_$mode.json" --keep-failed "${extra[@]+"${extra[@]}"}" "${analysis[@]+"${analysis[@]}"}" \
    > /dev/null 2> "$dir/pad_$mode.stderr"
  echo "   exit $? ($(tail -c 300 "$dir/pad_$mode.stderr" | tr '\n' ' '))" >&2
done

python3 - "$out" "$mode" <<'PY'
import json, os, sys, glob
out, mode = sys.argv[1], sys.argv[2]
print("| model | #H | #Sv | #Se | mSJ | aSJ | #H2+ | optimize s | HF | #H padded | #Sv | #Se | mSJ | aSJ | #H2+ | Hausdorff % | plan s | insertion s | optimization s | check |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for rep in sorted(glob.glob(os.path.join(out, "*", f"pad_{mode}.json"))):
    d = os.path.dirname(rep)
    j = json.load(open(rep))
    name = os.path.basename(d).replace("_", "/", 1)
    hf = j.get("analysis", {}).get("hard_facets", "-")
    plan = j.get("analysis", {}).get("seconds", 0) + j.get("selection", {}).get("seconds", 0)
    if "after" not in j:  # selective: nothing to pad
        print(f"| {name} | | | | | | | | {hf} | nothing to pad | | | | | | | {plan:.1f} | | | |")
        continue
    run = json.load(open(os.path.join(d, "report.json")))
    opt = {s["stage"]: s["seconds"] for s in run["stages"]}.get("optimize", 0)
    b, a = j["before"], j["after"]
    print(f"| {name} | {b['hexes']} | {b['singular_vertices']} | {b['singular_edges']} | {b['scaled_jacobian']['min']:.3f} | "
          f"{b['scaled_jacobian']['average']:.3f} | {b['multi_boundary_hexes']} | {opt:.0f} | {hf} | {a['hexes']} | {a['singular_vertices']} | "
          f"{a['singular_edges']} | {a['scaled_jacobian']['min']:.3f} | {a['scaled_jacobian']['average']:.3f} | "
          f"{a['multi_boundary_hexes']} | {100 * j['hausdorff']['relative']:.3f} | {plan:.1f} | {j['seconds']['insertion']:.3f} | "
          f"{j['seconds']['optimization']:.0f} | {'ok' if j['check']['ok'] else j['check']['reason']} |")
PY
