#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""kd_section_tables.py - the tables of bench/kd_section.sh from its runs' JSON lines.

usage: kd_section_tables.py rays RAYS.jsonl        (bench_kd_rays --json)
       kd_section_tables.py bunny KD.jsonl TSV     (rtcl bench --accel kd, thesis_kd_numbers.tsv)
"""
import json
import statistics
import sys


def rays(path):
    print("| scene | rays | query | backend | BVH min / median ms | kd min / median ms "
          "| kd / BVH (median) | Mrays/s BVH / kd | steps / ray BVH / kd "
          "| tri tests / ray BVH / kd | differ |")
    print("|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for line in open(path):
        r = json.loads(line)
        print(f"| {r['scene']} | {r['rays']} | {r['query']} | {r['backend']} "
              f"| {r['bvh_ms_min']:.1f} / {r['bvh_ms_median']:.1f} "
              f"| {r['kd_ms_min']:.1f} / {r['kd_ms_median']:.1f} "
              f"| {r['kd_ms_median'] / r['bvh_ms_median']:.2f}x "
              f"| {r['bvh_mrays']:.2f} / {r['kd_mrays']:.2f} "
              f"| {r['bvh_steps']:.1f} / {r['kd_steps']:.1f} "
              f"| {r['bvh_tri_tests']:.1f} / {r['kd_tri_tests']:.1f} | {r['differ']} |")


def bunny(kd_path, tsv):
    print("| source | method | hardware | Bunny build ms | note |")
    print("|---|---|---|---:|---|")
    for line in open(tsv):
        if line.startswith("#") or not line.strip():
            continue
        f = line.rstrip("\n").split("\t")
        print(f"| {f[0]} | {f[1]} | {f[2]} | {f[3]} | {f[4]} |")
    rows = {}
    for line in open(kd_path):
        run = json.loads(line)
        if "bunny" not in run["scene"]:
            continue
        for b in run["build"]:
            if b["builder"].startswith("kd-") and b.get("ms_min") is not None:
                rows.setdefault(b["builder"], []).append(b)
    for name, bs in rows.items():
        what = ("exact SAH, event sweep with perfect splits" if name == "kd-exact"
                else "binned SAH")
        mn = min(b["ms_min"] for b in bs)
        md = statistics.median(b["ms_median"] for b in bs)
        print(f"| this run ({name}) | {what} | this machine, {bs[-1]['threads']} threads "
              f"| {mn:.0f} (median {md:.0f}) | SAH {bs[-1]['sah']:.2f}, {bs[-1]['nodes']} nodes |")


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "rays":
        rays(sys.argv[2])
    elif len(sys.argv) == 4 and sys.argv[1] == "bunny":
        bunny(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)
