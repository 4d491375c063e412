#!/usr/bin/env python3
"""Markdown tables of a geombench run, one per scene, from its results.csv.

    python3 scripts/geombench-tables.py out/bench/results.csv > tables.md

Each cell: error_visible / error_cast / error_self (% of their pixels wrong) /
shadow-pass time in ms, and the projection drawn where it is not the technique's
own (a fallback, six faces); the soft techniques add their light-fraction error.
"""
import csv
import sys
from collections import OrderedDict


def cell(r):
    pct = lambda k: "%.3f" % (100 * float(r[k]))
    text = "%s / %s / %s / %.1f" % (pct("error_visible"), pct("error_cast"), pct("error_self"), float(r["time_ms"]))
    if r["technique"].endswith("-soft"):
        text += " / frac %.4f" % float(r["error_fraction"])
    return text


def main(path):
    scenes = OrderedDict()
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            scenes.setdefault((r["scene"], r["triangles"]), OrderedDict()).setdefault(r["technique"], []).append(r)
    sizes = ["256", "512", "1024", "2048", "4096"]
    for (scene, triangles), techniques in scenes.items():
        print("**%s** (%s triangles)\n" % (scene, "{:,}".format(int(triangles))))
        print("| technique | drawn | " + " | ".join(sizes) + " |")
        print("|---|---|" + "---|" * len(sizes))
        for technique, rows in techniques.items():
            drawn = "; ".join(OrderedDict.fromkeys(r["projection"] for r in rows))
            by_size = {r["shadow_map_size"]: r for r in rows}
            if "0" in by_size:  # the shadow volumes: no map, one cell
                cells = [cell(by_size["0"])] + [""] * (len(sizes) - 1)
            else:
                cells = [cell(by_size[s]) if s in by_size else "" for s in sizes]
            print("| %s | %s | %s |" % (technique, drawn, " | ".join(cells)))
        print()


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: geombench-tables.py RESULTS.csv")
    main(sys.argv[1])
