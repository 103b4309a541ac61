#!/usr/bin/env python3
"""Our support figures against PrusaSlicer's, on the parts `polycube fabricate` wrote.

    bench/slicer_support.py [--diagonal MM] PARTS_DIR...

Each PARTS_DIR is a folder with parts.json and print/part_NN.stl (each part standing on its
chosen base). Every part is sliced by PrusaSlicer with support on at the same overhang angle
(45 degrees), each model scaled so that its parts' whole bounding box has the given diagonal
(150 mm by default: the shared models are in units a printer cannot resolve; one factor per
model keeps its parts' ranks). Prints, per part, our support percentage and the filament
PrusaSlicer extrudes as support; then Spearman's rho per model and over all the parts, and the
parts where we say none is needed (no overhanging area, keel or tip) but PrusaSlicer prints
some. Standard library only.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile


def support_filament(gcode):
    """Filament (mm) extruded in the ;TYPE: sections naming support, absolute or relative E."""
    support, relative, e, total = False, False, 0.0, 0.0
    word = re.compile(r"\sE(-?[0-9.]+)")
    with open(gcode) as f:
        for line in f:
            if line.startswith(";TYPE:"):
                support = "Support" in line
            elif line.startswith("M83"):
                relative = True
            elif line.startswith("M82"):
                relative = False
            elif line.startswith(("G1", "G92")):
                m = word.search(line)
                if not m:
                    continue
                value = float(m.group(1))
                if line.startswith("G92"):
                    e = value
                    continue
                step = value if relative else value - e
                if not relative:
                    e = value
                if support and step > 0:
                    total += step
    return total


def ranks(x):
    order = sorted(range(len(x)), key=lambda i: x[i])
    r = [0.0] * len(x)
    i = 0
    while i < len(order):
        j = i
        while j + 1 < len(order) and x[order[j + 1]] == x[order[i]]:
            j += 1
        for k in range(i, j + 1):
            r[order[k]] = (i + j) / 2 + 1
        i = j + 1
    return r


def spearman(a, b):
    ra, rb = ranks(a), ranks(b)
    ma, mb = sum(ra) / len(ra), sum(rb) / len(rb)
    num = sum((x - ma) * (y - mb) for x, y in zip(ra, rb))
    den = math.sqrt(sum((x - ma) ** 2 for x in ra) * sum((y - mb) ** 2 for y in rb))
    return num / den if den > 0 else float("nan")


def model_scale(parts, diagonal):
    lo = [min(p["bounding_box"]["min"][a] for p in parts) for a in range(3)]
    hi = [max(p["bounding_box"]["max"][a] for p in parts) for a in range(3)]
    return diagonal / math.dist(lo, hi)


def slice_part(stl, scale, work):
    gcode = os.path.join(work, os.path.basename(os.path.dirname(os.path.dirname(stl))) + "_" +
                         os.path.basename(stl) + ".gcode")
    command = ["prusa-slicer", "--datadir", os.path.join(work, "config"), "--export-gcode",
               "--support-material", "--support-material-threshold", "45",
               "--bed-shape", "0x0,1000x0,1000x1000,0x1000", "--max-print-height", "1000",
               "--center", "500,500", "--scale", f"{scale:.9g}", "-o", gcode, stl]
    r = subprocess.run(command, capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"prusa-slicer failed on {stl}: {r.stderr.strip()[-300:]}")
    return support_filament(gcode)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("dirs", nargs="+", metavar="PARTS_DIR")
    parser.add_argument("--diagonal", type=float, default=150.0,
                        help="each model's size on the printer, mm (default 150)")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for d in args.dirs:
            parts = json.load(open(os.path.join(d, "parts.json")))["parts"]
            scale = model_scale(parts, args.diagonal)
            name = os.path.basename(os.path.dirname(os.path.abspath(d))) \
                if os.path.basename(os.path.abspath(d)) == "parts" else os.path.basename(d)
            for p in parts:
                if p.get("print_file") is None:
                    print(f"{name} {p['file']}: no base, not sliced", file=sys.stderr)
                    continue
                filament = slice_part(os.path.join(d, p["print_file"]), scale, work)
                rows.append((name, p["file"], p["support_percent"], filament,
                             p.get("needs_support", p["support_percent"] > 0)))
                print(f"| {name} | {p['file']} | {p['support_percent']:.3f} | {filament:.1f} |",
                      flush=True)
    print()
    for name in dict.fromkeys(r[0] for r in rows):
        sel = [r for r in rows if r[0] == name]
        rho = spearman([r[2] for r in sel], [r[3] for r in sel]) if len(sel) > 2 else float("nan")
        print(f"{name}: {len(sel)} parts, rho {rho:.3f}")
    print(f"all: {len(rows)} parts, rho {spearman([r[2] for r in rows], [r[3] for r in rows]):.3f}")
    missed = [r for r in rows if not r[4] and r[3] > 0]
    print(f"parts we say need no support that PrusaSlicer supports: {len(missed)}"
          + "".join(f"\n  {r[0]} {r[1]}: {r[3]:.1f} mm of filament" for r in missed))


if __name__ == "__main__":
    main()
