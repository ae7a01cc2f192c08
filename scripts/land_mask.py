#!/usr/bin/env python3
"""Makes assets/earth/land_mask.png, the 1 km land/sea mask of atmos, from the PyPI
wheel global-land-mask 1.0.0 (Todd Karin, MIT; the mask of NOAA's GLOBE 30" elevation
grid, whose "no data" cells are the sea).

Called by scripts/fetch_land_mask.sh, which fetches and checks the wheel:

    land_mask.py WHEEL OUT_PNG

The wheel's globe_combined_mask_compressed.npz holds `mask`, a 21600 x 43200 boolean
array (True = sea), row 0 from latitude 90 N, column 0 from longitude 180 W, one cell per
30 arc seconds: cell (i, j) is centred on longitude -180 + (i + 0.5) / 120 and latitude
90 - (j + 0.5) / 120 (the package's `lat_to_index` and `lon_to_index` floor into it),
the layout of the other maps in assets/earth/. The output is a 1-bit grey PNG of the same
size, 1 = land (lakes count as land, as in GLOBE), written with zlib by the small writer
below: only the Python standard library is needed. Deterministic: the same wheel gives
the same bytes.
"""

import struct
import sys
import zipfile
import zlib

WIDTH, HEIGHT = 43200, 21600
NPZ = "global_land_mask/globe_combined_mask_compressed.npz"
# Sea (True, byte 1) -> bit 0; land (False, byte 0) -> bit 1.
TO_BINARY_DIGITS = bytes.maketrans(b"\x00\x01", b"10")


def npy_rows(wheel):
    """The mask's rows, north first, as bytes of 0 (land) and 1 (sea)."""
    with zipfile.ZipFile(wheel) as outer, outer.open(NPZ) as npz_file:
        with zipfile.ZipFile(npz_file) as npz, npz.open("mask.npy") as f:
            magic = f.read(8)
            if magic[:6] != b"\x93NUMPY" or magic[6] != 1:
                raise ValueError(f"{wheel}: mask.npy is not a version 1 .npy file")
            (header_len,) = struct.unpack("<H", f.read(2))
            header = f.read(header_len).decode("latin-1")
            expected = f"'shape': ({HEIGHT}, {WIDTH})"
            if "'|b1'" not in header or "'fortran_order': False" not in header or expected not in header:
                raise ValueError(f"{wheel}: unexpected mask.npy header {header.strip()}")
            for _ in range(HEIGHT):
                row = f.read(WIDTH)
                if len(row) != WIDTH:
                    raise ValueError(f"{wheel}: mask.npy is truncated")
                yield row


def chunk(kind, data):
    body = kind + data
    return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body))


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: land_mask.py WHEEL OUT_PNG")
    wheel, out_path = sys.argv[1:]
    compressor = zlib.compressobj(9)
    idat = []
    land = 0
    for row in npy_rows(wheel):
        digits = row.translate(TO_BINARY_DIGITS)
        land += digits.count(b"1")
        packed = int(digits, 2).to_bytes(WIDTH // 8, "big")
        idat.append(compressor.compress(b"\x00" + packed))  # filter type 0 (none)
    idat.append(compressor.flush())
    # IHDR: width, height, bit depth 1, colour type 0 (grey), deflate, adaptive, no interlace.
    header = struct.pack(">IIBBBBB", WIDTH, HEIGHT, 1, 0, 0, 0, 0)
    with open(out_path, "wb") as out:
        out.write(b"\x89PNG\r\n\x1a\n")
        out.write(chunk(b"IHDR", header))
        out.write(chunk(b"IDAT", b"".join(idat)))
        out.write(chunk(b"IEND", b""))
    print(f"land fraction of cells {land / (WIDTH * HEIGHT):.4f}", file=sys.stderr)


if __name__ == "__main__":
    main()
