#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""build_table.py - turns `rtcl bench --json` lines (stdin) into the markdown
table of docs/BENCHMARKS.md, so that no number there is typed by hand.

Columns: min / median ms per builder, time and SAH ratios of `fast` to Embree's
rtcBuildBVH, SAH of the thesis and sah trees, node counts."""
import json
import os
import sys

BUILDERS = ["thesis-scalar", "thesis-neon", "thesis-mt", "sah", "embree"]


def main():
    rows = [json.loads(line) for line in sys.stdin if line.strip().startswith("{")]
    head = ["scene", "triangles"] + [f"{b} ms (min / med)" for b in BUILDERS] + [
        "sah/embree time (min)", "SAH thesis", "SAH sah", "SAH embree", "nodes sah / embree"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        by = {b["builder"]: b for b in r["build"]}
        name = "/".join(r["scene"].split(os.sep)[-2:])
        cells = [name, f"{r['triangles']:,}"]
        for b in BUILDERS:
            x = by.get(b)
            cells.append(f"{x['ms_min']:.2f} / {x['ms_median']:.2f}" if x and x.get("ms_min") is not None else "-")
        f, e = by.get("sah"), by.get("embree")
        cells.append(f"{f['ms_min'] / e['ms_min']:.2f}" if f and e and e.get("ms_min") else "-")
        for b in ["thesis-scalar", "sah", "embree"]:
            x = by.get(b)
            cells.append(f"{x['sah']:.2f}" if x and x.get("sah") is not None else "-")
        cells.append(f"{f['nodes']} / {e['nodes']}" if f and e else "-")
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
