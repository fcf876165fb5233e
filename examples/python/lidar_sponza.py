# SPDX-License-Identifier: Apache-2.0
"""A lidar scan of Sponza from a sensor moving down the nave, written as a
point cloud with normals (binary PLY). usage: lidar_sponza.py [SPONZA.obj] [OUT.ply]"""
import sys

import numpy as np
import rtcl

scene = rtcl.Scene.load(sys.argv[1] if len(sys.argv) > 1 else
                        "../shared/scenes/sponza_dabrovic/sponza.obj")
out = sys.argv[2] if len(sys.argv) > 2 else "sponza_scan.ply"
azimuth, elevation = np.meshgrid(np.radians(np.arange(0.0, 360.0, 0.5)),
                                 np.radians(np.linspace(-30.0, 30.0, 32)))  # 32 channels
beams = np.stack([np.cos(elevation) * np.cos(azimuth), np.sin(elevation),
                  np.cos(elevation) * np.sin(azimuth)], axis=-1).reshape(-1, 3).astype(np.float32)
clouds = []
for x in np.linspace(-12.0, 12.0, 25):  # 25 sensor positions, 23,040 beams each
    origin = np.array([x, 3.0, 0.0], np.float32)
    hit = scene.cast_rays(origin, beams, tmax=40.0)  # one origin for every beam
    ok = hit["t_hit"] < np.inf
    points = origin + hit["t_hit"][ok, None] * beams[ok]
    clouds.append(np.concatenate([points, hit["primitive_normals"][ok]], axis=1))
cloud = np.concatenate(clouds).astype("<f4")
with open(out, "wb") as f:
    f.write(b"ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(cloud))
    f.write(b"".join(b"property float %s\n" % k for k in (b"x", b"y", b"z", b"nx", b"ny", b"nz")))
    f.write(b"end_header\n" + cloud.tobytes())
print("%s: %d points from %d beams" % (out, len(cloud), 25 * len(beams)))
