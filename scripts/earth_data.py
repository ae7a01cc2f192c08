#!/usr/bin/env python3
"""Makes the Earth colour and height maps of atmos from the two source files.

Called by scripts/fetch_earth_data.sh, which fetches the sources and installs Pillow:

    earth_data.py BMNG_JPG ETOPO5_CDF OUT_DIR

Writes OUT_DIR/colour.jpg and OUT_DIR/height.png, both equirectangular, north up, the
first column starting at 180 degrees west, pixel (i, j) centred on longitude
-180 + (i + 0.5) * 360 / width and latitude 90 - (j + 0.5) * 180 / height:

- colour.jpg: NASA Blue Marble (bmng.jpg, 5400 x 2700) resampled to COLOUR_SIZE with
  Pillow's Lanczos filter, JPEG quality COLOUR_QUALITY.
- height.png: ETOPO5 (2161 x 4320 nodes every 5 arc minutes, poles included, longitude
  0 to 359.92 east) filtered onto HEIGHT_SIZE pixel centres, which fall on nodes, with a
  separable [1, 2, 1] / 4 tent (each pixel averages its 10' x 10' cell), rounded to whole
  metres, stored as 16-bit grey: value = metres + HEIGHT_OFFSET_M.

The NetCDF file is read by the small classic-format (CDF-1/CDF-2) reader below, so the
only dependency is Pillow. Deterministic: the same inputs and Pillow give the same bytes.
"""

import array
import struct
import sys

from PIL import Image

COLOUR_SIZE = (4096, 2048)
COLOUR_QUALITY = 90
HEIGHT_SIZE = (2160, 1080)
HEIGHT_OFFSET_M = 11000

# NetCDF classic external types: NC_BYTE, NC_CHAR, NC_SHORT, NC_INT, NC_FLOAT, NC_DOUBLE.
NC_TYPES = {1: ("b", 1), 2: ("c", 1), 3: ("h", 2), 4: ("i", 4), 5: ("f", 4), 6: ("d", 8)}
NC_DIMENSION, NC_VARIABLE, NC_ATTRIBUTE = 0x0A, 0x0B, 0x0C


class NetCdfClassic:
    """The header of a NetCDF classic file (the format spec's `header` production), and
    non-record variables read whole as big-endian arrays."""

    def __init__(self, path):
        with open(path, "rb") as f:
            self.data = f.read()
        if self.data[:3] != b"CDF" or self.data[3] not in (1, 2):
            raise ValueError(f"{path}: not a NetCDF classic (CDF-1 or CDF-2) file")
        self.offset_size = 8 if self.data[3] == 2 else 4
        self.pos = 4
        self._u32()  # numrecs
        self.dims = [(self._name(), self._u32()) for _ in range(self._list(NC_DIMENSION))]
        self._attributes()  # global attributes
        self.vars = {}
        for _ in range(self._list(NC_VARIABLE)):
            name = self._name()
            dim_ids = [self._u32() for _ in range(self._u32())]
            attributes = self._attributes()
            nc_type = self._u32()
            self._u32()  # vsize
            begin = self._u64() if self.offset_size == 8 else self._u32()
            shape = [self.dims[i][1] for i in dim_ids]
            self.vars[name] = (shape, nc_type, begin, attributes)

    def _u32(self):
        (value,) = struct.unpack_from(">I", self.data, self.pos)
        self.pos += 4
        return value

    def _u64(self):
        (value,) = struct.unpack_from(">Q", self.data, self.pos)
        self.pos += 8
        return value

    def _padded(self, n):
        raw = self.data[self.pos : self.pos + n]
        self.pos += (n + 3) // 4 * 4
        return raw

    def _name(self):
        return self._padded(self._u32()).decode("utf-8")

    def _list(self, tag):
        found, count = self._u32(), self._u32()
        if found not in (tag, 0):
            raise ValueError(f"NetCDF header: expected list tag {tag:#x}, found {found:#x}")
        return count

    def _attributes(self):
        attributes = {}
        for _ in range(self._list(NC_ATTRIBUTE)):
            name = self._name()
            code, size = NC_TYPES[self._u32()]
            count = self._u32()
            raw = self._padded(count * size)
            if code == "c":
                attributes[name] = raw.decode("latin-1").rstrip("\0")
            else:
                attributes[name] = struct.unpack(f">{count}{code}", raw)
        return attributes

    def variable(self, name):
        """The variable's values, row-major, as a native-endian `array.array`."""
        shape, nc_type, begin, _ = self.vars[name]
        code, size = NC_TYPES[nc_type]
        count = 1
        for n in shape:
            count *= n
        values = array.array(code)
        values.frombytes(self.data[begin : begin + count * size])
        if sys.byteorder == "little":
            values.byteswap()
        return shape, values


def colour_map(bmng_path, out_path):
    with Image.open(bmng_path) as image:
        image = image.convert("RGB").resize(COLOUR_SIZE, Image.Resampling.LANCZOS)
    image.save(out_path, "JPEG", quality=COLOUR_QUALITY, optimize=True)


def height_map(etopo_path, out_path):
    cdf = NetCdfClassic(etopo_path)
    (ny,), lat = cdf.variable("ETOPO05_Y")
    (nx,), lon = cdf.variable("ETOPO05_X")
    (rows, cols), rose = cdf.variable("ROSE")
    if (rows, cols) != (ny, nx) or (ny, nx) != (2161, 4320):
        raise ValueError(f"{etopo_path}: expected ROSE[2161][4320], found [{rows}][{cols}]")
    if abs(lat[0] + 90) > 1e-6 or abs(lat[-1] - 90) > 1e-6 or abs(lon[0]) > 1e-6:
        raise ValueError(f"{etopo_path}: unexpected grid (lat {lat[0]}..{lat[-1]}, lon {lon[0]}..)")
    missing = cdf.vars["ROSE"][3].get("missing_value", (None,))[0]
    if missing is not None and any(v == missing for v in rose):
        raise ValueError(f"{etopo_path}: ROSE has missing values")

    width, height = HEIGHT_SIZE
    step = nx // width  # nodes per pixel: 2
    half = nx // 2  # longitude 180 east = 180 west: the output's first column

    def node(row_from_north, col_from_180w):
        return rose[(ny - 1 - row_from_north) * nx + (col_from_180w + half) % nx]

    weights = ((0, 0.25), (1, 0.5), (2, 0.25))
    out = array.array("H", bytes(2 * width * height))
    for j in range(height):
        r0 = step * j  # the pixel's centre is node row r0 + 1 from the north pole
        for i in range(width):
            c0 = step * i
            metres = 0.0
            for dr, wr in weights:
                for dc, wc in weights:
                    metres += wr * wc * node(r0 + dr, c0 + dc)
            value = int(round(metres)) + HEIGHT_OFFSET_M
            if not 0 <= value <= 0xFFFF:
                raise ValueError(f"height {metres} m does not fit the 16-bit encoding")
            out[j * width + i] = value
    if sys.byteorder == "big":
        out.byteswap()
    Image.frombytes("I;16", HEIGHT_SIZE, out.tobytes()).save(out_path, "PNG", optimize=True)


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: earth_data.py BMNG_JPG ETOPO5_CDF OUT_DIR")
    bmng, etopo, out_dir = sys.argv[1:]
    colour_map(bmng, f"{out_dir}/colour.jpg")
    height_map(etopo, f"{out_dir}/height.png")


if __name__ == "__main__":
    main()
