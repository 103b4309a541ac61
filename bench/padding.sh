#!/usr/bin/env bash
# Global padding (`polycube pad`) of every optimized hex mesh bench/chain.sh left in OUT, with
# the input surface as target; prints the table of thesis Table 4.1's "Global Padding" columns
# (markdown): #H, #Sv, #Se, mSJ, aSJ without and with padding, and the time of each step.
# Usage: bench/padding.sh [build-dir]
#   env: OUT=out/bench (chain.sh's output), ONLY="surface/bunny tet/cup ..." pads just those.
set -uo pipefail
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
out=${OUT:-$root/out/bench}
if [[ "$build" = /* ]]; then pc=$build/polycube; else pc=$root/$build/polycube; fi
[[ -x "$pc" ]] || { echo "bench/padding.sh: $pc not found; run make first" >&2; exit 2; }

for rep in "$out"/*/report.json; do
  dir=$(dirname "$rep"); key=$(basename "$dir"); kind=${key%%_*}; name=${key#*_}
  if [[ -n "${ONLY:-}" && " $ONLY " != *" $kind/$name "* ]]; then continue; fi
  [[ -f "$dir/hex_optimized.mesh" ]] || { echo "== $kind/$name: no hex_optimized.mesh, skipped" >&2; continue; }
  input=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["input"])' "$rep")
  echo "== $kind/$name" >&2
  "$pc" -q pad "$dir/hex_optimized.mesh" --target "$input" -o "$dir/hex_global.mesh" --vtk "$dir/hex_global.vtk" \
    --report "$dir/pad_global.json" --keep-failed > /dev/null 2> "$dir/pad_global.stderr"
  echo "   exit $? ($(tail -c 300 "$dir/pad_global.stderr" | tr '\n' ' '))" >&2
done

python3 - "$out" <<'PY'
import json, os, sys, glob
out = sys.argv[1]
print("| model | #H | #Sv | #Se | mSJ | aSJ | #H2+ | optimize s | #H padded | #Sv | #Se | mSJ | aSJ | #H2+ | Hausdorff % | insertion s | optimization s | check |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
for rep in sorted(glob.glob(os.path.join(out, "*", "pad_global.json"))):
    d = os.path.dirname(rep)
    j = json.load(open(rep))
    run = json.load(open(os.path.join(d, "report.json")))
    opt = {s["stage"]: s["seconds"] for s in run["stages"]}.get("optimize", 0)
    b, a = j["before"], j["after"]
    name = os.path.basename(d).replace("_", "/", 1)
    print(f"| {name} | {b['hexes']} | {b['singular_vertices']} | {b['singular_edges']} | {b['scaled_jacobian']['min']:.3f} | "
          f"{b['scaled_jacobian']['average']:.3f} | {b['multi_boundary_hexes']} | {opt:.0f} | {a['hexes']} | {a['singular_vertices']} | "
          f"{a['singular_edges']} | {a['scaled_jacobian']['min']:.3f} | {a['scaled_jacobian']['average']:.3f} | "
          f"{a['multi_boundary_hexes']} | {100 * j['hausdorff']['relative']:.3f} | {j['seconds']['insertion']:.3f} | "
          f"{j['seconds']['optimization']:.0f} | {'ok' if j['check']['ok'] else j['check']['reason']} |")
PY
