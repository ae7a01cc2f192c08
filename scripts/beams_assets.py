#!/usr/bin/env python3
"""Writes the light maps and the mesh of the shipped beams scenes (assets/scenes/beams/).

    python3 scripts/beams_assets.py [OUT_DIR]

- gobo_{star,bars,dots,ring,leaves}.png: 64 x 64 grey gobos for the five spotlights of
  stage_five_spots.toml (Dobashi et al. 2000 Table 1: 64 x 64 light maps), white where
  light passes, with soft edges (2 x 2 supersampling).
- stained_glass.png: a 128 x 128 stained-glass window (Table 1: 128 x 128 for the
  sunlight of Fig. 8b): coloured panes in lead cames, for stained_glass_room.toml.
- pillar.gltf: an octagonal pillar, 0.4 m in radius and 3 m tall on y = 0, its buffer
  embedded as a base64 data URI, for stage_five_spots.toml.

Standard library only; the same script writes the same bytes.
"""

import base64
import json
import math
import os
import struct
import sys
import zlib


def write_png(path, width, height, pixel):
    """An 8-bit RGB PNG whose pixel (x, y) (y down) is pixel(x, y) = (r, g, b) in 0..255."""
    rows = bytearray()
    for y in range(height):
        rows.append(0)
        for x in range(width):
            rows.extend(pixel(x, y))

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))

    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
    png += chunk(b"IDAT", zlib.compress(bytes(rows), 9)) + chunk(b"IEND", b"")
    with open(path, "wb") as f:
        f.write(png)


def supersampled(inside, size):
    """A grey pixel function: the fraction of 2 x 2 subsamples where inside(u, v) holds,
    u and v in [-1, 1] (v up)."""

    def pixel(x, y):
        hits = 0
        for sx in (0.25, 0.75):
            for sy in (0.25, 0.75):
                u = 2.0 * (x + sx) / size - 1.0
                v = 1.0 - 2.0 * (y + sy) / size
                hits += 1 if inside(u, v) else 0
        g = round(255 * hits / 4)
        return (g, g, g)

    return pixel


def star(u, v):
    r, a = math.hypot(u, v), math.atan2(v, u)
    return r < 0.45 + 0.4 * abs(math.cos(2.5 * a)) ** 3


def bars(u, v):
    return math.hypot(u, v) < 0.95 and math.floor((u + 1.0) * 4.0) % 2 == 0


def dots(u, v):
    cu, cv = round(u * 2.5) / 2.5, round(v * 2.5) / 2.5
    return math.hypot(u, v) < 0.95 and math.hypot(u - cu, v - cv) < 0.14


def ring(u, v):
    r = math.hypot(u, v)
    return 0.55 < r < 0.8 or r < 0.2


def leaves(u, v):
    r, a = math.hypot(u, v), math.atan2(v, u)
    wobble = math.sin(7.0 * a + 3.0 * r) * math.sin(5.0 * r * 3.0)
    return r < 0.95 and wobble > 0.1


PANES = [(200, 30, 40), (30, 60, 200), (240, 200, 40), (40, 160, 70), (150, 40, 170), (250, 130, 30)]


def stained_glass(x, y):
    """Coloured panes in a grid of diamonds, dark lead cames between them, a round
    rose in the middle."""
    size = 128
    u, v = 2.0 * (x + 0.5) / size - 1.0, 1.0 - 2.0 * (y + 0.5) / size
    r = math.hypot(u, v)
    if abs(r - 0.42) < 0.03 or abs(u) > 0.97 or abs(v) > 0.97:
        return (20, 20, 20)
    if r < 0.42:
        petal = int(((math.atan2(v, u) + math.pi) / (2 * math.pi)) * 8) % len(PANES)
        return PANES[petal] if r > 0.1 else (250, 240, 200)
    a, b = (u + v) * 4.0, (u - v) * 4.0
    if min(a - math.floor(a), b - math.floor(b)) < 0.07:
        return (20, 20, 20)
    return PANES[(int(math.floor(a)) * 3 + int(math.floor(b))) % len(PANES)]


def pillar_gltf(path, radius=0.4, height=3.0, sides=8):
    """An octagonal prism: side quads and two caps, as indexed triangles."""
    positions = []
    for k in range(sides):
        a = 2.0 * math.pi * k / sides
        x, z = radius * math.cos(a), radius * math.sin(a)
        positions += [(x, 0.0, z), (x, height, z)]
    positions += [(0.0, 0.0, 0.0), (0.0, height, 0.0)]
    bottom, top = 2 * sides, 2 * sides + 1
    indices = []
    for k in range(sides):
        a0, a1 = 2 * k, 2 * ((k + 1) % sides)
        indices += [a0, a0 + 1, a1 + 1, a0, a1 + 1, a1]
        indices += [bottom, a1, a0, top, a0 + 1, a1 + 1]
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    index_offset = len(data)
    data += b"".join(struct.pack("<H", i) for i in indices)
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    document = {
        "asset": {"version": "2.0", "generator": "scripts/beams_assets.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "Pillar", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [
            {
                "byteLength": len(data),
                "uri": "data:application/octet-stream;base64,"
                + base64.b64encode(data).decode("ascii"),
            }
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": index_offset},
            {"buffer": 0, "byteOffset": index_offset, "byteLength": len(data) - index_offset},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions), "type": "VEC3",
             "min": lo, "max": hi},
            {"bufferView": 1, "componentType": 5123, "count": len(indices), "type": "SCALAR"},
        ],
    }
    with open(path, "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "assets", "scenes", "beams")
    os.makedirs(out, exist_ok=True)
    for name, inside in [("star", star), ("bars", bars), ("dots", dots), ("ring", ring),
                         ("leaves", leaves)]:
        write_png(os.path.join(out, f"gobo_{name}.png"), 64, 64, supersampled(inside, 64))
    write_png(os.path.join(out, "stained_glass.png"), 128, 128, stained_glass)
    pillar_gltf(os.path.join(out, "pillar.gltf"))


if __name__ == "__main__":
    main()
