#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# incoherent_report.sh RTCL SHARED_SCENES [RAYS] [REPS] [--quick] - the incoherent-ray
# section of docs/BENCHMARKS.md (issue 20), as Markdown on stdout: one
# 'rtcl bench --incoherent' run per scene (Sponza's and Sibenik's interior
# views, the bunny, the 871k dragon: no Whitted frames; the shipped Cornell
# box: with its Whitted frames at 1024x576), 2 threads, then the tables.
# --quick: the bunny and the Cornell box only (report.sh --quick).
# Called by bench/report.sh; callable alone, to refresh just this section:
#   bash bench/incoherent_report.sh build/rtcl ../shared/scenes 1000000 5
set -euo pipefail
rtcl=${1:?usage: incoherent_report.sh RTCL SHARED_SCENES [RAYS] [REPS]}
shared=${2:?usage: incoherent_report.sh RTCL SHARED_SCENES [RAYS] [REPS]}
rays=${3:-1000000}
reps=${4:-5}
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
scenes=("$here/scenes/sponza_interior.json" "$shared/stanford_bunny/stanford-bunny.obj"
        "$shared/stanford_dragon/dragon_vrip.obj" "$here/scenes/sibenik_interior.json")
[ "${5:-}" = --quick ] && scenes=("$shared/stanford_bunny/stanford-bunny.obj")
for s in "${scenes[@]}"; do
    [ -f "$s" ] || { echo "incoherent_report.sh: no $s" >&2; exit 2; }
    echo "incoherent_report.sh: $(basename "$s")" >&2
    "$rtcl" bench "$s" --incoherent --json --rays "$rays" --reps "$reps" --threads 2 --no-render \
        >>"$tmp/rows.jsonl"
done
echo "incoherent_report.sh: cornell.json with Whitted frames" >&2
"$rtcl" bench "$root/scenes/cornell.json" --incoherent --json --rays "$rays" --reps "$reps" \
    --threads 2 >>"$tmp/rows.jsonl"

rel() { local p=$1; p=${p#"$root/"}; echo "${p/#$shared/\$S}"; }
cmd="build/rtcl bench SCENE --incoherent --json --rays $rays --reps $reps --threads 2 --no-render"
cat <<MD
\`\`\`sh
S=../shared/scenes
for SCENE in $(for s in "${scenes[@]}"; do printf '%s ' "$(rel "$s")"; done); do
    $cmd
done
build/rtcl bench scenes/cornell.json --incoherent --json --rays $rays --reps $reps --threads 2
\`\`\`

MD
python3 - "$tmp/rows.jsonl" <<'PY'
import json, math, sys, os
objs = [json.loads(l) for l in open(sys.argv[1]) if l.strip()]
def f(x): return "%.3f" % x
def gm(v): return math.exp(sum(map(math.log, v)) / len(v)) if v else float("nan")
print("Each cell: Mrays/s at the min time / at the median time of %d interleaved rounds "
      "(after one warm-up round), %d rays per set, 2 threads; the speed columns are ours "
      "against Embree's in the same rounds (its time over ours, min and median: above 1, "
      "ours is faster); *differ*: packet hits unlike the oracle's, bit for bit."
      % (objs[0]["reps"], objs[0]["rays_per_set"]))
print()
print("| scene | triangles | rays | query | cpu (oracle) | packet (auto) | Embree 1 | Embree 16 "
      "| packet / Embree 1 | packet / Embree 16 | cpu / Embree 1 | differ |")
print("|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
ratios = {}
for o in objs:
    name = os.path.basename(o["scene"])
    keyed = {}
    for r in o["incoherent"]:
        keyed[(r["rays"], r["query"], r["path"])] = r
    for rays in ("diffuse", "random"):
        for q in ("closest", "any"):
            e1 = "rtcIntersect1" if q == "closest" else "rtcOccluded1"
            e16 = "rtcIntersect16" if q == "closest" else "rtcOccluded16"
            cells = []
            for p in ("cpu", "packet-auto", e1, e16):
                r = keyed.get((rays, q, p))
                cells.append("%s / %s" % (f(r["mrays_min"]), f(r["mrays_median"])) if r else "-")
            pk, cpu = keyed[(rays, q, "packet-auto")], keyed[(rays, q, "cpu")]
            def rat(r, k):
                if ("vs_%s_min" % k) not in r: return "-"
                return "%.2f, %.2f" % (r["vs_%s_min" % k], r["vs_%s_median" % k])
            if "vs_embree1_min" in pk:
                ratios.setdefault(q, []).append((pk["vs_embree1_min"], pk["vs_embree1_median"]))
            print("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %d |" % (
                name, o["triangles"], rays, q, *cells, rat(pk, "embree1"), rat(pk, "embree16"),
                rat(cpu, "embree1"), pk["differ_from_oracle"]))
    if "embree_absent" in o:
        print("\nNo Embree rows for %s: %s" % (name, o["embree_absent"]))
print()
for q, v in ratios.items():
    mins, meds = [a for a, _ in v], [b for _, b in v]
    print("Geometric mean over these scenes, packet against Embree's single rays, %s: %.2f at the "
          "min (range %.2f-%.2f), %.2f at the median (range %.2f-%.2f)." % (
              "closest hit" if q == "closest" else "any hit", gm(mins), min(mins), max(mins),
              gm(meds), min(meds), max(meds)))
for o in objs:
    if not o.get("whitted"): continue
    print()
    print("Whitted frames of %s at %dx%d, 2 threads, min / median of %d frames after the first, "
          "interleaved:" % (os.path.basename(o["scene"]), o["whitted_width"], o["whitted_height"],
                            o["reps"]))
    print()
    print("| backend | secondary rays | ms (min / median) | Mrays/s (median) |")
    print("|---|---|---:|---:|")
    for w in o["whitted"]:
        print("| %s | %s | %.1f / %.1f | %.3f |" % (w["backend"], w["secondary"], w["ms_min"],
                                                   w["ms_median"], w["mrays_median"]))
    print()
    print("Not measurable any more: %s." % o["whitted_packet_oracle_secondary"])
PY
