#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""view_fps.py - frames per second of 'rtcl view', the real-time viewer, on
each backend, beside Embree rendering the same frames ('rtcl bench').

Usage (under a display; xvfb-run -a python3 bench/view_fps.py ... on a
machine without one):
    view_fps.py RTCL REPS FRAMES SCENE...

Each session plays the scene's timeline (--play: objects with keyframes step
through them at 10 a second, a keyframe change every third frame, each one a
BVH rebuild) for FRAMES frames at the scene's resolution on a fixed clock
(--step 33.333, --move-scale 1: every frame at full resolution), with 2
threads, once with direct lighting (primary and shadow rays, the thesis's
benchmark set-up, which 'rtcl bench' renders for Embree too) and once
Whitted. Sessions run round by round (every scene, backend and lighting once
a round, REPS rounds), each round followed by 'rtcl bench SCENE --reps 5
--threads 2' for Embree's frame time in that round. The viewer's own
numbers: its closing line, the frames per second over the frames after the
first and the median update, render and present times (presenting frame k
overlaps rendering frame k+1). Prints a markdown table: per scene, backend
and lighting the min and median over the rounds of the session fps, the
median times, and for direct lighting Embree's fastest packet width's
median frame time over the viewer's frame period at its median fps (1.0:
the viewer, window and all, as fast as Embree tracing the same rays)."""
import json
import re
import statistics
import subprocess
import sys

rtcl, reps, frames, scenes = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4:]
backends = ["cpu", "packet", "opencl"]
line_re = re.compile(
    r"view: (\d+) frames; after the first: ([0-9.]+) fps; median ms: update ([0-9.]+), "
    r"render ([0-9.]+), present ([0-9.]+) \(presenting overlaps the next frame's render\); "
    r"(.*), (\d+) triangles")

runs = {}   # (scene, backend, lighting) -> list of (fps, frame, update, render, present)
embree = {}  # scene -> list of Embree's fastest median ms, one per round
for rnd in range(reps):
    for scene in scenes:
        for backend in backends:
            for lighting in ("direct", "whitted"):
                cmd = [rtcl, "view", scene, "--backend", backend, "--frames", str(frames),
                       "--play", "--step", "33.333", "--move-scale", "1", "--threads", "2"]
                if lighting == "direct":
                    cmd.append("--direct")
                out = subprocess.run(cmd, capture_output=True, text=True)
                m = line_re.search(out.stdout)
                if out.returncode != 0 or not m:
                    sys.exit(f"{' '.join(cmd)} failed: {out.stdout} {out.stderr}")
                runs.setdefault((scene, backend, lighting), []).append(
                    tuple(float(m.group(i)) for i in (2, 3, 4, 5)) + (m.group(6),))
        out = subprocess.run([rtcl, "bench", scene, "--json", "--reps", "5", "--threads", "2"],
                             capture_output=True, text=True, check=True)
        rows = json.loads(out.stdout.strip().splitlines()[-1])["render"]
        best = min(r["ms_median"] for r in rows if r["backend"].startswith("embree"))
        embree.setdefault(scene, []).append(best)

print("| scene | backend | lighting | fps min / median | median ms: update, render, present "
      "| Embree frame ms (median) | Embree ms / viewer frame period |")
print("|---|---|---|---|---|---|---|")
for scene in scenes:
    for backend in backends:
        for lighting in ("direct", "whitted"):
            r = runs[(scene, backend, lighting)]
            fps = [x[0] for x in r]
            period = 1000.0 / statistics.median(fps)
            parts = [statistics.median(x[i] for x in r) for i in (1, 2, 3)]
            e = statistics.median(embree[scene]) if lighting == "direct" else None
            name = scene.split("/")[-1]
            print(f"| {name} | {r[-1][4]} | {lighting} | {min(fps):.2f} / "
                  f"{statistics.median(fps):.2f} | {parts[0]:.1f}, {parts[1]:.1f}, "
                  f"{parts[2]:.1f} | {f'{e:.1f}' if e else '-'} | "
                  f"{f'{e / period:.2f}' if e else '-'} |")
