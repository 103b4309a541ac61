#!/usr/bin/env bash
# The demo: the main job on a built-in sample, results under OUT (default out/demo).
# Usage: scripts/demo.sh path/to/polycube [out-dir]
set -euo pipefail
pc=${1:?usage: demo.sh path/to/polycube [out-dir]}
out=${2:-out/demo}
mkdir -p "$out"

echo "== built-in samples"
"$pc" sample --list

echo
echo "== box-cylinder sample (thesis fig. 4.2) -> $out/box-cylinder.obj"
"$pc" sample box-cylinder -o "$out/box-cylinder.obj"
"$pc" info "$out/box-cylinder.obj"

echo
echo "== the whole chain: construct -> simplify -> hexmesh (+ quad mesh) -> optimize -> $out/run/"
if "$pc" run "$out/box-cylinder.obj" -o "$out/run" --hexes 5000; then
  echo
  echo "Open $out/run/hex_quality.vtk (cell data scaled_jacobian, block_id) and $out/run/quad.vtk in ParaView;"
  echo "$out/run/hex_optimized.mesh opens in Gmsh. Every stage's result and report.json are in $out/run/."
else
  echo "(the chain stopped; the message above names the stage, $out/run/report.json has the details)"
  exit 3
fi
