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
- teapot.gltf and teapot.bin: the Newell (Utah) teapot for teapot_spotlight.toml (after
  Dobashi et al. 2000 Fig. 7a), its 32 bicubic Bezier patches (public-domain data)
  evaluated on 8 x 8 quads each, scaled by 0.4 (1.26 m tall) with z up turned to y up,
  degenerate triangles (where a patch closes to a point) left out.

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


# The Newell (Utah) teapot: 32 bicubic Bezier patches, each 16 indices (1-based) into 306
# control points (x, y, z), z up (Newell 1975; the data as published by Crow 1987).
TEAPOT_PATCHES = """
1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16
4 17 18 19 8 20 21 22 12 23 24 25 16 26 27 28
19 29 30 31 22 32 33 34 25 35 36 37 28 38 39 40
31 41 42 1 34 43 44 5 37 45 46 9 40 47 48 13
13 14 15 16 49 50 51 52 53 54 55 56 57 58 59 60
16 26 27 28 52 61 62 63 56 64 65 66 60 67 68 69
28 38 39 40 63 70 71 72 66 73 74 75 69 76 77 78
40 47 48 13 72 79 80 49 75 81 82 53 78 83 84 57
57 58 59 60 85 86 87 88 89 90 91 92 93 94 95 96
60 67 68 69 88 97 98 99 92 100 101 102 96 103 104 105
69 76 77 78 99 106 107 108 102 109 110 111 105 112 113 114
78 83 84 57 108 115 116 85 111 117 118 89 114 119 120 93
121 122 123 124 125 126 127 128 129 130 131 132 133 134 135 136
124 137 138 121 128 139 140 125 132 141 142 129 136 143 144 133
133 134 135 136 145 146 147 148 149 150 151 152 69 153 154 155
136 143 144 133 148 156 157 145 152 158 159 149 155 160 161 69
162 163 164 165 166 167 168 169 170 171 172 173 174 175 176 177
165 178 179 162 169 180 181 166 173 182 183 170 177 184 185 174
174 175 176 177 186 187 188 189 190 191 192 193 194 195 196 197
177 184 185 174 189 198 199 186 193 200 201 190 197 202 203 194
204 204 204 204 207 208 209 210 211 211 211 211 212 213 214 215
204 204 204 204 210 217 218 219 211 211 211 211 215 220 221 222
204 204 204 204 219 224 225 226 211 211 211 211 222 227 228 229
204 204 204 204 226 230 231 207 211 211 211 211 229 232 233 212
212 213 214 215 234 235 236 237 238 239 240 241 242 243 244 245
215 220 221 222 237 246 247 248 241 249 250 251 245 252 253 254
222 227 228 229 248 255 256 257 251 258 259 260 254 261 262 263
229 232 233 212 257 264 265 234 260 266 267 238 263 268 269 242
270 270 270 270 279 280 281 282 275 276 277 278 271 272 273 274
270 270 270 270 282 289 290 291 278 286 287 288 274 283 284 285
270 270 270 270 291 298 299 300 288 295 296 297 285 292 293 294
270 270 270 270 300 305 306 279 297 303 304 275 294 301 302 271
"""

TEAPOT_POINTS = """
1.4,0.0,2.4 1.4,-0.784,2.4 0.784,-1.4,2.4 0.0,-1.4,2.4
1.3375,0.0,2.53125 1.3375,-0.749,2.53125 0.749,-1.3375,2.53125 0.0,-1.3375,2.53125
1.4375,0.0,2.53125 1.4375,-0.805,2.53125 0.805,-1.4375,2.53125 0.0,-1.4375,2.53125
1.5,0.0,2.4 1.5,-0.84,2.4 0.84,-1.5,2.4 0.0,-1.5,2.4
-0.784,-1.4,2.4 -1.4,-0.784,2.4 -1.4,0.0,2.4 -0.749,-1.3375,2.53125
-1.3375,-0.749,2.53125 -1.3375,0.0,2.53125 -0.805,-1.4375,2.53125 -1.4375,-0.805,2.53125
-1.4375,0.0,2.53125 -0.84,-1.5,2.4 -1.5,-0.84,2.4 -1.5,0.0,2.4
-1.4,0.784,2.4 -0.784,1.4,2.4 0.0,1.4,2.4 -1.3375,0.749,2.53125
-0.749,1.3375,2.53125 0.0,1.3375,2.53125 -1.4375,0.805,2.53125 -0.805,1.4375,2.53125
0.0,1.4375,2.53125 -1.5,0.84,2.4 -0.84,1.5,2.4 0.0,1.5,2.4
0.784,1.4,2.4 1.4,0.784,2.4 0.749,1.3375,2.53125 1.3375,0.749,2.53125
0.805,1.4375,2.53125 1.4375,0.805,2.53125 0.84,1.5,2.4 1.5,0.84,2.4
1.75,0.0,1.875 1.75,-0.98,1.875 0.98,-1.75,1.875 0.0,-1.75,1.875
2.0,0.0,1.35 2.0,-1.12,1.35 1.12,-2.0,1.35 0.0,-2.0,1.35
2.0,0.0,0.9 2.0,-1.12,0.9 1.12,-2.0,0.9 0.0,-2.0,0.9
-0.98,-1.75,1.875 -1.75,-0.98,1.875 -1.75,0.0,1.875 -1.12,-2.0,1.35
-2.0,-1.12,1.35 -2.0,0.0,1.35 -1.12,-2.0,0.9 -2.0,-1.12,0.9
-2.0,0.0,0.9 -1.75,0.98,1.875 -0.98,1.75,1.875 0.0,1.75,1.875
-2.0,1.12,1.35 -1.12,2.0,1.35 0.0,2.0,1.35 -2.0,1.12,0.9
-1.12,2.0,0.9 0.0,2.0,0.9 0.98,1.75,1.875 1.75,0.98,1.875
1.12,2.0,1.35 2.0,1.12,1.35 1.12,2.0,0.9 2.0,1.12,0.9
2.0,0.0,0.45 2.0,-1.12,0.45 1.12,-2.0,0.45 0.0,-2.0,0.45
1.5,0.0,0.225 1.5,-0.84,0.225 0.84,-1.5,0.225 0.0,-1.5,0.225
1.5,0.0,0.15 1.5,-0.84,0.15 0.84,-1.5,0.15 0.0,-1.5,0.15
-1.12,-2.0,0.45 -2.0,-1.12,0.45 -2.0,0.0,0.45 -0.84,-1.5,0.225
-1.5,-0.84,0.225 -1.5,0.0,0.225 -0.84,-1.5,0.15 -1.5,-0.84,0.15
-1.5,0.0,0.15 -2.0,1.12,0.45 -1.12,2.0,0.45 0.0,2.0,0.45
-1.5,0.84,0.225 -0.84,1.5,0.225 0.0,1.5,0.225 -1.5,0.84,0.15
-0.84,1.5,0.15 0.0,1.5,0.15 1.12,2.0,0.45 2.0,1.12,0.45
0.84,1.5,0.225 1.5,0.84,0.225 0.84,1.5,0.15 1.5,0.84,0.15
-1.6,0.0,2.025 -1.6,-0.3,2.025 -1.5,-0.3,2.25 -1.5,0.0,2.25
-2.3,0.0,2.025 -2.3,-0.3,2.025 -2.5,-0.3,2.25 -2.5,0.0,2.25
-2.7,0.0,2.025 -2.7,-0.3,2.025 -3.0,-0.3,2.25 -3.0,0.0,2.25
-2.7,0.0,1.8 -2.7,-0.3,1.8 -3.0,-0.3,1.8 -3.0,0.0,1.8
-1.5,0.3,2.25 -1.6,0.3,2.025 -2.5,0.3,2.25 -2.3,0.3,2.025
-3.0,0.3,2.25 -2.7,0.3,2.025 -3.0,0.3,1.8 -2.7,0.3,1.8
-2.7,0.0,1.575 -2.7,-0.3,1.575 -3.0,-0.3,1.35 -3.0,0.0,1.35
-2.5,0.0,1.125 -2.5,-0.3,1.125 -2.65,-0.3,0.9375 -2.65,0.0,0.9375
-2.0,-0.3,0.9 -1.9,-0.3,0.6 -1.9,0.0,0.6 -3.0,0.3,1.35
-2.7,0.3,1.575 -2.65,0.3,0.9375 -2.5,0.3,1.125 -1.9,0.3,0.6
-2.0,0.3,0.9 1.7,0.0,1.425 1.7,-0.66,1.425 1.7,-0.66,0.6
1.7,0.0,0.6 2.6,0.0,1.425 2.6,-0.66,1.425 3.1,-0.66,0.825
3.1,0.0,0.825 2.3,0.0,2.1 2.3,-0.25,2.1 2.4,-0.25,2.025
2.4,0.0,2.025 2.7,0.0,2.4 2.7,-0.25,2.4 3.3,-0.25,2.4
3.3,0.0,2.4 1.7,0.66,0.6 1.7,0.66,1.425 3.1,0.66,0.825
2.6,0.66,1.425 2.4,0.25,2.025 2.3,0.25,2.1 3.3,0.25,2.4
2.7,0.25,2.4 2.8,0.0,2.475 2.8,-0.25,2.475 3.525,-0.25,2.49375
3.525,0.0,2.49375 2.9,0.0,2.475 2.9,-0.15,2.475 3.45,-0.15,2.5125
3.45,0.0,2.5125 2.8,0.0,2.4 2.8,-0.15,2.4 3.2,-0.15,2.4
3.2,0.0,2.4 3.525,0.25,2.49375 2.8,0.25,2.475 3.45,0.15,2.5125
2.9,0.15,2.475 3.2,0.15,2.4 2.8,0.15,2.4 0.0,0.0,3.15
0.0,-0.002,3.15 0.002,0.0,3.15 0.8,0.0,3.15 0.8,-0.45,3.15
0.45,-0.8,3.15 0.0,-0.8,3.15 0.0,0.0,2.85 0.2,0.0,2.7
0.2,-0.112,2.7 0.112,-0.2,2.7 0.0,-0.2,2.7 -0.002,0.0,3.15
-0.45,-0.8,3.15 -0.8,-0.45,3.15 -0.8,0.0,3.15 -0.112,-0.2,2.7
-0.2,-0.112,2.7 -0.2,0.0,2.7 0.0,0.002,3.15 -0.8,0.45,3.15
-0.45,0.8,3.15 0.0,0.8,3.15 -0.2,0.112,2.7 -0.112,0.2,2.7
0.0,0.2,2.7 0.45,0.8,3.15 0.8,0.45,3.15 0.112,0.2,2.7
0.2,0.112,2.7 0.4,0.0,2.55 0.4,-0.224,2.55 0.224,-0.4,2.55
0.0,-0.4,2.55 1.3,0.0,2.55 1.3,-0.728,2.55 0.728,-1.3,2.55
0.0,-1.3,2.55 1.3,0.0,2.4 1.3,-0.728,2.4 0.728,-1.3,2.4
0.0,-1.3,2.4 -0.224,-0.4,2.55 -0.4,-0.224,2.55 -0.4,0.0,2.55
-0.728,-1.3,2.55 -1.3,-0.728,2.55 -1.3,0.0,2.55 -0.728,-1.3,2.4
-1.3,-0.728,2.4 -1.3,0.0,2.4 -0.4,0.224,2.55 -0.224,0.4,2.55
0.0,0.4,2.55 -1.3,0.728,2.55 -0.728,1.3,2.55 0.0,1.3,2.55
-1.3,0.728,2.4 -0.728,1.3,2.4 0.0,1.3,2.4 0.224,0.4,2.55
0.4,0.224,2.55 0.728,1.3,2.55 1.3,0.728,2.55 0.728,1.3,2.4
1.3,0.728,2.4 0.0,0.0,0.0 1.5,0.0,0.15 1.5,0.84,0.15
0.84,1.5,0.15 0.0,1.5,0.15 1.5,0.0,0.075 1.5,0.84,0.075
0.84,1.5,0.075 0.0,1.5,0.075 1.425,0.0,0.0 1.425,0.798,0.0
0.798,1.425,0.0 0.0,1.425,0.0 -0.84,1.5,0.15 -1.5,0.84,0.15
-1.5,0.0,0.15 -0.84,1.5,0.075 -1.5,0.84,0.075 -1.5,0.0,0.075
-0.798,1.425,0.0 -1.425,0.798,0.0 -1.425,0.0,0.0 -1.5,-0.84,0.15
-0.84,-1.5,0.15 0.0,-1.5,0.15 -1.5,-0.84,0.075 -0.84,-1.5,0.075
0.0,-1.5,0.075 -1.425,-0.798,0.0 -0.798,-1.425,0.0 0.0,-1.425,0.0
0.84,-1.5,0.15 1.5,-0.84,0.15 0.84,-1.5,0.075 1.5,-0.84,0.075
0.798,-1.425,0.0 1.425,-0.798,0.0
"""

def bezier_patch_point(control, u, v):
    """The bicubic Bezier patch of 4 x 4 control points (row-major) at (u, v)."""

    def basis(t):
        s = 1.0 - t
        return (s * s * s, 3.0 * s * s * t, 3.0 * s * t * t, t * t * t)

    bu, bv = basis(u), basis(v)
    return tuple(sum(bu[i] * bv[j] * control[4 * i + j][c] for i in range(4) for j in range(4))
                 for c in range(3))


def teapot_gltf(folder, scale=0.4, quads=8):
    """teapot.gltf and its buffer teapot.bin: each patch on quads x quads cells, two
    triangles a cell, the teapot's z up turned to glTF's y up."""
    points = [tuple(float(c) for c in p.split(",")) for p in TEAPOT_POINTS.split()]
    patches = [[int(i) - 1 for i in line.split()] for line in TEAPOT_PATCHES.strip().splitlines()]
    positions, indices = [], []
    for patch in patches:
        control = [points[i] for i in patch]
        base = len(positions)
        for i in range(quads + 1):
            for j in range(quads + 1):
                x, y, z = bezier_patch_point(control, i / quads, j / quads)
                positions.append((scale * x, scale * z, -scale * y))
        for i in range(quads):
            for j in range(quads):
                a = base + i * (quads + 1) + j
                b, c, d = a + 1, a + quads + 1, a + quads + 2
                for tri in ((a, c, d), (a, d, b)):
                    if triangle_area(*(positions[k] for k in tri)) > 1e-12:
                        indices.extend(tri)
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    index_offset = len(data)
    data += b"".join(struct.pack("<H", i) for i in indices)
    with open(os.path.join(folder, "teapot.bin"), "wb") as f:
        f.write(data)
    lo = [min(p[i] for p in positions) for i in range(3)]
    hi = [max(p[i] for p in positions) for i in range(3)]
    document = {
        "asset": {"version": "2.0", "generator": "scripts/beams_assets.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "Teapot", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data), "uri": "teapot.bin"}],
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
    with open(os.path.join(folder, "teapot.gltf"), "w") as f:
        json.dump(document, f, indent=1)
        f.write("\n")


def triangle_area(a, b, c):
    """The area of the triangle abc."""
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return 0.5 * math.sqrt(sum(x * x for x in n))


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "assets", "scenes", "beams")
    os.makedirs(out, exist_ok=True)
    for name, inside in [("star", star), ("bars", bars), ("dots", dots), ("ring", ring),
                         ("leaves", leaves)]:
        write_png(os.path.join(out, f"gobo_{name}.png"), 64, 64, supersampled(inside, 64))
    write_png(os.path.join(out, "stained_glass.png"), 128, 128, stained_glass)
    pillar_gltf(os.path.join(out, "pillar.gltf"))
    teapot_gltf(out)


if __name__ == "__main__":
    main()
