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
echo "== polycube labeling of the sample -> $out/label/"
"$pc" label "$out/box-cylinder.obj" -o "$out/label" || echo "(labeling did not reach a valid result; see $out/label/report.json)"
