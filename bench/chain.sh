#!/usr/bin/env bash
# The whole chain (`polycube run`) over every model of ../shared/data (surfaces and tet meshes)
# and every built-in sample; prints one table (markdown) and writes it, with the machine, to
# bench/RESULTS.md when --write is given.
# Usage: bench/chain.sh [--write] [--table-only] [build-dir]
#   env: HEXES=20000, TIME_LIMIT (construct budget; default: the tool's), OUT=out/bench; ONLY="surface/bunny tet/cup ..." runs just
#   those models (kind/name; several lanes can share one OUT); --table-only rebuilds the table
#   from OUT without running anything.
set -uo pipefail
write=0
table_only=0
while [[ "${1:-}" == --* ]]; do
  case "$1" in
    --write) write=1 ;;
    --table-only) table_only=1 ;;
    *) echo "bench/chain.sh: unknown option $1" >&2; exit 2 ;;
  esac
  shift
done
build=${1:-build}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
data=${DATA:-$root/../shared/data}
out=${OUT:-$root/out/bench}
hexes=${HEXES:-20000}
limit_opt=()
[[ -n "${TIME_LIMIT:-}" ]] && limit_opt=(--time-limit "$TIME_LIMIT")
if [[ "$build" = /* ]]; then pc=$build/polycube; else pc=$root/$build/polycube; fi
[[ -x "$pc" ]] || { echo "bench/chain.sh: $pc not found; run make first" >&2; exit 2; }
mkdir -p "$out"

inputs=()
[[ $table_only -eq 1 ]] || for f in "$data"/surface/*.obj "$data"/tet/*.mesh; do [[ -f "$f" ]] && inputs+=("$f"); done
[[ $table_only -eq 1 ]] || for s in $("$pc" sample --list | awk '{print $1}'); do
  "$pc" -q sample "$s" -o "$out/sample_$s.obj" && inputs+=("$out/sample_$s.obj")
done

for f in "${inputs[@]+"${inputs[@]}"}"; do
  kind=$(basename "$(dirname "$f")"); name=$(basename "${f%.*}")
  [[ "$name" == sample_* ]] && { kind=sample; name=${name#sample_}; }
  if [[ -n "${ONLY:-}" && " $ONLY " != *" $kind/$name "* ]]; then continue; fi
  dir="$out/${kind}_$name"
  rm -rf "$dir"
  echo "== $kind/$name" >&2
  "$pc" -q run "$f" -o "$dir" --hexes "$hexes" "${limit_opt[@]+"${limit_opt[@]}"}" > /dev/null 2> "$dir.stderr"
  echo "   exit $? ($(tail -c 300 "$dir.stderr" | tr '\n' ' '))" >&2
done

table=$(python3 - "$out" <<'PY'
import json, os, sys, glob
out = sys.argv[1]
def f(v, spec):
    return "-" if v is None or (isinstance(v, (int, float)) and v < -1.5) or v == -1 else format(v, spec)
rows = []
print("| model | #tets | #charts | #corners | #D before | #D after | #dom before | #dom after | #H | mSJ | aSJ | Hausdorff | construct s | simplify s | hexmesh s | optimize s | total s | peak MiB | attempt | simplify step | optimize fallback | result |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|---|---|")
for rep in sorted(glob.glob(os.path.join(out, "*", "report.json"))):
    j = json.load(open(rep))
    name = os.path.basename(os.path.dirname(rep)).replace("_", "/", 1)
    st = {s["stage"]: s["seconds"] for s in j["stages"]}
    fin = j["final"]
    res = "ok" if j["ok"] else "failed at " + j["failure"]["stage"]
    print("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |".format(
        name, f(j["tets"], "d"), f(j["charts"], "d"), f(j["corners"], "d"),
        f(j["hex_domains_before"], "d"), f(j["hex_domains_after"], "d"),
        f(j["quad_domains_before"], "d"), f(j["quad_domains_after"], "d"), f(j["hexes"], "d"),
        f(fin["msj"], ".3f"), f(fin["asj"], ".3f"), f(fin["hausdorff_relative"], ".4f"),
        f(st.get("construct"), ".1f"), f(st.get("simplify"), ".1f"), f(st.get("hexmesh"), ".1f"),
        f(st.get("optimize"), ".1f"), f(j["total_seconds"], ".1f"), f(j["peak_memory_mib"], ".0f"),
        (j.get("construct_attempt") or "-") + ("" if not j.get("construct_fallback") else
            ", of the " + j["construct_fallback"]["taken"].split(" (")[0] +
            " (Hausdorff from the input {:.4f})".format(fin.get("hausdorff_unwrapped_relative") or -1)),
        j.get("simplify_step") or "-", j.get("optimize_fallback") or "-", res))
PY
)
echo "$table"
if [[ $write -eq 1 ]]; then
  {
    echo "# Benchmark: the whole chain (\`bench/chain.sh\`)"
    echo
    echo "Machine: $(nproc) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2/1048576}' /proc/meminfo), $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); $(uname -sr)."
    echo "Date: $(date -u +%Y-%m-%d). Commit: $(git -C "$root" rev-parse --short HEAD). Options: \`polycube run --hexes $hexes ${limit_opt[*]+${limit_opt[*]}}\` (defaults otherwise)."
    echo "Fallbacks: the construction attempt kept (the first planned is \"compactness 1\"), the simplification step (\"aligned\" unless it fell back) and the optimize stage's (\"none\": the first grid passed)."
    echo "Hausdorff: final hex boundary vs the input surface, relative to its bounding-box diagonal. mSJ/aSJ: after optimization."
    echo
    echo "$table"
  } > "$here/RESULTS.md"
  echo "wrote $here/RESULTS.md" >&2
fi
