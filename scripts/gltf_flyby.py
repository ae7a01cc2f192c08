#!/usr/bin/env python3
"""Writes assets/paths/gltf_flyby.gltf, the camera animation of gltf_flyby.toml.

    python3 scripts/gltf_flyby.py [OUT.gltf]

One perspective camera node, "Camera", and one animation, "CameraAction", as Blender's
exporter writes them: glTF axes (x east, y up, -z north once the path places the
scene), metres, times in seconds. Over 12 s the camera flies 1.9 km ahead while
climbing 240 m, yawing left and back, looking 5 degrees down; translation and rotation
are LINEAR samplers with keyframes every 3 s. The buffer is embedded as a base64 data
URI. Standard library only; the same script writes the same bytes.
"""

import base64
import json
import math
import struct
import sys

TIMES = [0.0, 3.0, 6.0, 9.0, 12.0]
# Metres in glTF axes: x east, y up, z south.
PLACES = [
    (0.0, 0.0, 0.0),
    (-100.0, 60.0, -500.0),
    (-350.0, 120.0, -950.0),
    (-600.0, 180.0, -1350.0),
    (-750.0, 240.0, -1800.0),
]
# Degrees turned left (about +y), and looking down (about +x).
YAW_DEG = [0.0, 20.0, 40.0, 30.0, 10.0]
PITCH_DEG = -5.0
YFOV_RAD = 0.7


def multiply(a, b):
    """Hamilton product of (x, y, z, w) quaternions."""
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (
        aw * bx + ax * bw + ay * bz - az * by,
        aw * by - ax * bz + ay * bw + az * bx,
        aw * bz + ax * by - ay * bx + az * bw,
        aw * bw - ax * bx - ay * by - az * bz,
    )


def axis_angle(axis, degrees):
    half = math.radians(degrees) / 2
    return tuple(c * math.sin(half) for c in axis) + (math.cos(half),)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else "assets/paths/gltf_flyby.gltf"
    rotations = [
        multiply(axis_angle((0, 1, 0), yaw), axis_angle((1, 0, 0), PITCH_DEG))
        for yaw in YAW_DEG
    ]
    floats = TIMES + [c for p in PLACES for c in p] + [c for q in rotations for c in q]
    data = struct.pack("<%df" % len(floats), *floats)
    n = len(TIMES)
    views = [(0, 4 * n), (4 * n, 12 * n), (16 * n, 16 * n)]
    gltf = {
        "asset": {"version": "2.0", "generator": "atmos scripts/gltf_flyby.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "Camera", "camera": 0}],
        "cameras": [
            {
                "name": "Camera",
                "type": "perspective",
                "perspective": {"yfov": YFOV_RAD, "znear": 0.1, "aspectRatio": 16 / 9},
            }
        ],
        "buffers": [
            {
                "byteLength": len(data),
                "uri": "data:application/octet-stream;base64,"
                + base64.b64encode(data).decode("ascii"),
            }
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": o, "byteLength": l} for o, l in views
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": n, "type": "SCALAR",
             "min": [TIMES[0]], "max": [TIMES[-1]]},
            {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": n, "type": "VEC4"},
        ],
        "animations": [
            {
                "name": "CameraAction",
                "channels": [
                    {"sampler": 0, "target": {"node": 0, "path": "translation"}},
                    {"sampler": 1, "target": {"node": 0, "path": "rotation"}},
                ],
                "samplers": [
                    {"input": 0, "output": 1, "interpolation": "LINEAR"},
                    {"input": 0, "output": 2, "interpolation": "LINEAR"},
                ],
            }
        ],
    }
    with open(out, "w", encoding="utf-8") as f:
        json.dump(gltf, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()
