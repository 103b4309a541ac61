#!/usr/bin/env python3
"""Thesis Table 4.1 from the outputs of bench/padding.sh run twice (MODE=global, then
MODE=selective) over bench/chain.sh's folders: for each model, the unpadded, globally padded and
selectively padded meshes (#H, #Sv, #Se, mSJ, aSJ), the hexes selective padding adds as a share
of what global padding adds, and the time of selective padding (plan = analysis + binary problem,
then insertion + optimization).

Usage: bench/table41.py OUT   (OUT: the folder of chain.sh's outputs, e.g. out/bench)
"""
import glob
import json
import os
import sys


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, ValueError):
        return None


def mesh_cells(m):
    sj = m["scaled_jacobian"]
    return [f"{m['hexes']:,}", str(m["singular_vertices"]), str(m["singular_edges"]),
            f"{sj['min']:.3f}", f"{sj['average']:.3f}"]


def check(j):
    if j is None:
        return "not run"
    if "after" not in j:
        return "ok"
    ok = j["check"]["ok"] and j["after"]["scaled_jacobian"]["inverted"] == 0
    return f"{'ok' if ok else j['check']['reason']}, {100 * j['hausdorff']['relative']:.2f} %"


def main(out):
    head = ["model", "#H", "#Sv", "#Se", "mSJ", "aSJ",
            "global #H", "#Sv", "#Se", "mSJ", "aSJ",
            "selective #H", "#Sv", "#Se", "mSJ", "aSJ", "added ÷ global's",
            "plan s", "binary problem", "insert + optimize s", "global: check, Hausdorff",
            "selective: check, Hausdorff"]
    print("| " + " | ".join(head) + " |")
    print("|---|" + "---:|" * 19 + "---|---|")
    for d in sorted(glob.glob(os.path.join(out, "*"))):
        g = load(os.path.join(d, "pad_global.json"))
        s = load(os.path.join(d, "pad_selective.json"))
        if g is None and s is None:
            continue
        name = os.path.basename(d).replace("_", "/", 1)
        before = (g or s).get("before")
        row = [name] + (mesh_cells(before) if before else [""] * 5)
        row += mesh_cells(g["after"]) if g and "after" in g else ["-"] * 5
        if s is None:
            row += ["not run"] + [""] * 5
        elif "after" not in s:  # the unpadded mesh is the result
            cells = mesh_cells(before) if before else [""] * 5
            row += [cells[0] + " (nothing to pad)"] + cells[1:] + ["0 %"]
        else:
            share = "-"
            if g and "after" in g and g["added_hexes"] > 0:
                share = f"{100 * s['added_hexes'] / g['added_hexes']:.0f} %"
            row += mesh_cells(s["after"]) + [share]
        if s is not None:
            a, sel = s.get("analysis", {}), s.get("selection", {})
            plan = a.get("seconds", 0) + sel.get("seconds", 0)
            if a.get("hard_facets", 0) == 0:
                how = "HF empty"
            elif sel.get("optimal"):
                how = f"HF {a['hard_facets']}, optimal"
            else:
                how = f"HF {a['hard_facets']}, gap {100 * sel.get('gap', 0):.1f} %"
            rest = s["seconds"]["insertion"] + s["seconds"]["optimization"] if "after" in s else 0
            row += [f"{plan:.1f}", how, f"{rest:.0f}"]
        else:
            row += ["", "", ""]
        row += [check(g), check(s)]
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
