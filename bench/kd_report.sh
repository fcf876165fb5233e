#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# kd_report.sh - the kd-tree numbers of docs/BENCHMARKS.md (issue 18): for
# each scene, ROUNDS rounds that alternate 'rtcl bench --accel bvh' and
# 'rtcl bench --accel kd' (so that a busy machine slows both alike), then a
# Markdown summary: build min/median ms, SAH, nodes and bytes of the BVH
# builders beside kd-exact and kd-binned, and frame ms, Mrays/s and tests per
# ray of each backend with BVH meshes and with kd meshes (primary plus shadow
# rays, the thesis's set-up), each against Embree in the same run.
#
# usage: bench/kd_report.sh RTCL ROUNDS REPS SCENE...
# KD_BENCH_ARGS: more rtcl bench options (e.g. "--width 512 --height 288")
# KD_KEEP_JSON: a folder to keep the runs' JSON lines in (bvh.jsonl, kd.jsonl)
set -eu
RTCL=$1 ROUNDS=$2 REPS=$3
shift 3
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for scene in "$@"; do
    for r in $(seq "$ROUNDS"); do
        for accel in bvh kd; do
            "$RTCL" bench "$scene" --json --reps "$REPS" --accel $accel ${KD_BENCH_ARGS:-} \
                >> "$tmp/$accel.jsonl"
        done
    done
done
if [ -n "${KD_KEEP_JSON:-}" ]; then cp "$tmp/bvh.jsonl" "$tmp/kd.jsonl" "$KD_KEEP_JSON/"; fi
python3 - "$tmp" << 'PY'
import json, statistics, sys, collections
tmp = sys.argv[1]
runs = {a: [json.loads(l) for l in open(f"{tmp}/{a}.jsonl")] for a in ("bvh", "kd")}
for scene in dict.fromkeys(r["scene"] for r in runs["bvh"]):
    bvh = [r for r in runs["bvh"] if r["scene"] == scene]
    kd = [r for r in runs["kd"] if r["scene"] == scene]
    print(f"\n#### {scene} ({bvh[0]['triangles']} triangles, {len(bvh)} rounds x {bvh[0]['reps']} reps)\n")
    print("| builder | threads | min ms | median ms | SAH (Ct 1, Ci 2) | nodes | MiB |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    rows = collections.OrderedDict()
    for run in bvh + kd:
        for b in run["build"]:
            if b.get("ms_min") is None: continue
            rows.setdefault(b["builder"], []).append(b)
    for name, bs in rows.items():
        mins = [b["ms_min"] for b in bs]; meds = [b["ms_median"] for b in bs]
        mib = f"{bs[-1]['bytes'] / 1048576:.2f}" if "bytes" in bs[-1] else "-"
        print(f"| {name} | {bs[-1]['threads']} | {min(mins):.1f} | {statistics.median(meds):.1f} | "
              f"{bs[-1]['sah']:.2f} | {bs[-1]['nodes']} | {mib} |")
    print(f"\n| backend | meshes | min ms | median ms | Mrays/s (median) | box or node steps / ray | tri tests / ray | vs embree (median) |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for label, group in (("bvh", bvh), ("kd", kd)):
        per = collections.OrderedDict()
        for run in group:
            for r in run.get("render", []):
                if r.get("ms_min") is None: continue
                per.setdefault(r["backend"], []).append(r)
        emb = per.get("embree")
        emb_med = statistics.median(r["ms_median"] for r in emb) if emb else None
        for name, rs in per.items():
            if name.startswith("embree") and label == "kd": continue
            med = statistics.median(r["ms_median"] for r in rs)
            mr = statistics.median(r["mrays"] for r in rs)
            bt = rs[-1].get("box_tests"); tt = rs[-1].get("tri_tests")
            bt = "-" if bt is None else round(bt, 1); tt = "-" if tt is None else round(tt, 1)
            ratio = f"{med / emb_med:.2f}x" if emb_med else "-"
            print(f"| {name} | {label} | {min(r['ms_min'] for r in rs):.1f} | {med:.1f} | {mr:.2f} | "
                  f"{bt} | {tt} | {ratio} |")
PY
