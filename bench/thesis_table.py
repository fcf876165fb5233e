#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""thesis_table.py THESIS_TSV < rtcl-bench-json - the thesis's own build times
(bench/thesis_numbers.tsv, copied from the thesis) beside ours for the same
scene, taken from this run's `rtcl bench --json` lines. The thesis ran on a
2013 phone; only orders of magnitude compare."""
import json
import sys


def main():
    ours = {}
    for line in sys.stdin:
        if line.strip().startswith("{"):
            o = json.loads(line)
            ours[o["scene"]] = (o["triangles"], {b["builder"]: b for b in o["build"]})
    print("| thesis scene (2013 phone) | triangles | thesis-mt build ms (phone) | our scene | "
          "our triangles | thesis-mt ms (min / med), this machine | sah ms (min / med) | note |")
    print("|---|---|---|---|---|---|---|---|")
    for line in open(sys.argv[1]):
        if line.startswith("#") or not line.strip():
            continue
        name, tris, ms, scene, note = line.rstrip("\n").split("\t")
        cells = [name, f"{int(tris):,}", ms, scene]
        match = [k for k in ours if scene != "-" and k.endswith(scene)]
        if match:
            n, by = ours[match[0]]
            cells.append(f"{n:,}")
            for b in ["thesis-mt", "sah"]:
                x = by.get(b)
                cells.append(f"{x['ms_min']:.2f} / {x['ms_median']:.2f}"
                             if x and x.get("ms_min") is not None else "-")
        else:
            cells += ["-", "-", "-"]
        cells.append(note)
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
