# SPDX-License-Identifier: Apache-2.0
"""Which random points lie inside the Stanford bunny: the parity of the
triangles a ray from each point crosses (each triangle once, rays through
shared edges and vertices counted exactly once). The scan has holes in its
base, through which a ray can leave without crossing, so each point votes
with five random directions. usage: inside_bunny.py [BUNNY.obj]"""
import sys

import numpy as np
import rtcl

scene = rtcl.Scene.load(sys.argv[1] if len(sys.argv) > 1 else
                        "../shared/scenes/stanford_bunny/stanford-bunny.obj")
rng = np.random.default_rng(1)
points = rng.uniform([-0.095, 0.033, -0.062], [0.061, 0.187, 0.059], (200000, 3))
votes = sum(scene.count_intersections(points, rng.standard_normal(points.shape)) % 2
            for _ in range(5))
inside = votes >= 3
print("%d of %d points inside (%.1f%% of the box, %.1f cm^3); %d without a clear vote"
      % (inside.sum(), len(points), 100.0 * inside.mean(),
         inside.mean() * np.prod([0.156, 0.154, 0.121]) * 1e6, ((votes > 0) & (votes < 5)).sum()))
