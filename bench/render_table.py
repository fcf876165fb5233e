#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""render_table.py - turns the "render" rows of `rtcl bench --json` lines
(stdin) into the markdown tables of docs/BENCHMARKS.md: frame times of our
backends beside Embree's, the ratios the issue's targets are judged by, and a
generated line on each target. No number here is typed by hand.

Ratios are rates (rays per second), i.e. the inverse of median frame times:
packet/embree = embree median ms / packet median ms; the same ratio of the
min times stands beside it (the least disturbed frames on a shared machine).
The targets are judged on the medians."""
import json
import os
import sys

OURS = ["cpu", "packet", "opencl"]


def cell_ms(r):
    if not r or r.get("ms_min") is None:
        return "-"
    return f"{r['ms_min']:.1f} / {r['ms_median']:.1f}"


def rate_ratio(a, b, key="ms_median"):
    """a's rate over b's rate (b's median time over a's, or min with key)."""
    if not a or not b or a.get(key) in (None, 0) or b.get(key) is None:
        return None
    return b[key] / a[key]


def fmt_ratio(median, least):
    return "-" if median is None else f"{median:.2f} ({fmt(least)})"


def fmt(x, digits=2):
    return "-" if x is None else f"{x:.{digits}f}"


def scene_name(path):
    return "/".join(path.split(os.sep)[-2:])


def main():
    objs = [json.loads(line) for line in sys.stdin if line.strip().startswith("{")]
    objs = [o for o in objs if o.get("render")]
    if not objs:
        sys.exit("render_table.py: no render rows in the input")
    w, h = objs[0]["render_width"], objs[0]["render_height"]
    threads = objs[0]["render"][0]["threads"]
    print(f"Frame time at {w}x{h}, ms (min / median); Mrays/s of the median frame "
          f"(primary plus shadow rays); {threads} threads everywhere.\n")
    head = ["scene", "triangles (all meshes)"] + [f"{b} ms" for b in OURS] + [
        "embree ms (best width)", "Mrays/s cpu / packet / opencl / embree",
        "packet / embree (by min)", "opencl / cpu (by min)", "box tests/ray", "tri tests/ray",
        "pixels differing visibly from cpu: packet / opencl / embree"]
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    # The targets are on the shared scenes; the shipped scenes (the
    # repository's scenes/) are shown but judged apart.
    shipped_dir = os.path.realpath(os.path.join(os.path.dirname(__file__), "..", "scenes")) + os.sep
    packet_vs_embree, opencl_vs_cpu = [], []
    packet_vs_embree_min, opencl_vs_cpu_min = [], []
    shipped = []
    widths = []
    for o in objs:
        by = {r["backend"]: r for r in o["render"]}
        e = by.get("embree")
        cells = [scene_name(o["scene"]), f"{o['triangles']:,}"]
        cells += [cell_ms(by.get(b)) for b in OURS]
        cells.append(f"{cell_ms(e)} ({e['lanes']})" if e and e.get("ms_min") is not None else "-")
        cells.append(" / ".join(fmt(by[b].get("mrays"), 1) if b in by and by[b].get("mrays") else "-"
                                for b in OURS + ["embree"]))
        pe = rate_ratio(by.get("packet"), e)
        oc = rate_ratio(by.get("opencl"), by.get("cpu"))
        pe_min = rate_ratio(by.get("packet"), e, "ms_min")
        oc_min = rate_ratio(by.get("opencl"), by.get("cpu"), "ms_min")
        if os.path.realpath(o["scene"]).startswith(shipped_dir):
            shipped.append((scene_name(o["scene"]), pe, oc))
        else:
            for ratio, into in ((pe, packet_vs_embree), (oc, opencl_vs_cpu),
                                (pe_min, packet_vs_embree_min), (oc_min, opencl_vs_cpu_min)):
                if ratio is not None:
                    into.append((ratio, scene_name(o["scene"])))
        cells += [fmt_ratio(pe, pe_min), fmt_ratio(oc, oc_min)]
        cpu = by.get("cpu", {})
        cells += [fmt(cpu.get("box_tests")), fmt(cpu.get("tri_tests"))]
        cells.append(" / ".join(str(by[b].get("pixels_visibly_differ_from_cpu", "-")) if b in by else "-"
                                for b in ["packet", "opencl", "embree"]))
        print("| " + " | ".join(cells) + " |")
        widths.append((scene_name(o["scene"]),
                       [(r["lanes"], r["ms_median"]) for r in o["render"]
                        if r["backend"].startswith("embree-") and r.get("ms_median") is not None]))

    print("\nEmbree by packet width (median ms): " + "; ".join(
        f"{name}: " + ", ".join(f"{lanes}: {ms:.1f}" for lanes, ms in ws) for name, ws in widths if ws) + ".")

    def judge(pairs, least, target, what):
        if not pairs:
            return f"- {what}: not measured (no shared scene in this run, or the backend is unavailable)."
        lo, hi = min(pairs), max(pairs)
        met = sum(1 for r, _ in pairs if r >= target)
        line = (f"- {what}, by median frame times: {lo[0]:.2f}x ({lo[1]}) to {hi[0]:.2f}x ({hi[1]}); "
                f"target {target}x {'met' if met == len(pairs) else 'NOT met'} "
                f"({met} of {len(pairs)} scenes)")
        if least:
            met_min = sum(1 for r, _ in least if r >= target)
            line += (f". By min frame times: {min(least)[0]:.2f}x to {max(least)[0]:.2f}x, "
                     f"{met_min} of {len(least)} scenes at or above {target}x")
        return line + "."

    print("\nAgainst the targets, on the shared scenes (computed from the table):\n")
    print(judge(packet_vs_embree, packet_vs_embree_min, 0.8,
                "packet rate / Embree's best packet rate"))
    print(judge(opencl_vs_cpu, opencl_vs_cpu_min, 1.5,
                "OpenCL (PoCL) rate / the scalar oracle's rate"))
    for name, pe, oc in shipped:
        print(f"- shipped scene {name} (not a shared scene; its objects are instances, which the "
              f"Embree peer gets flattened into one world-space BVH): packet / embree "
              f"{fmt(pe)}x, opencl / cpu {fmt(oc)}x.")


if __name__ == "__main__":
    main()
