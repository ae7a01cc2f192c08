//! The 1 km land/sea mask: `assets/earth/land_mask.png`, a 1-bit grey PNG of 43200 x 21600
//! cells of 30 arc seconds, 1 = land (NOAA GLOBE's cells with data, lakes included; see
//! `assets/CREDITS.md`), in the equirectangular layout of `geo_grid.rs`.
//!
//! Held as tiles of 32 x 32 cells: a tile all land or all sea is one flag, a tile the
//! coast crosses keeps its bits (32 rows of 32). The PNG is decoded row by row, so the
//! full grid (117 MB of bits) is never in memory at once.

use std::io::Cursor;
use std::path::Path;

use super::geo_grid::bilinear_taps;
use super::map_error::MapError;

/// Cells along a tile's side.
const TILE: usize = 32;

#[derive(Clone, Debug, PartialEq, Eq)]
enum Tile {
    Sea,
    Land,
    /// Row `r` of the tile in element `r`, column `c` in bit `c` (1 = land).
    Coast(Box<[u32; TILE]>),
}

/// A land/sea mask on an equirectangular grid.
#[derive(Clone, Debug)]
pub struct LandMask {
    pub width: usize,
    pub height: usize,
    tiles_across: usize,
    tiles: Vec<Tile>,
}

impl LandMask {
    /// Decodes a 1-bit grey PNG (1 = land) whose sides are multiples of 32 and whose width
    /// is twice its height; `path` names it in errors.
    pub fn decode(bytes: &[u8], path: &Path) -> Result<LandMask, MapError> {
        let read_error = |e: png::DecodingError| MapError::Read {
            path: path.to_owned(),
            source: image::ImageError::Decoding(image::error::DecodingError::new(
                image::ImageFormat::Png.into(),
                e,
            )),
        };
        let mut decoder = png::Decoder::new(Cursor::new(bytes));
        decoder.set_transformations(png::Transformations::IDENTITY);
        let mut reader = decoder.read_info().map_err(read_error)?;
        let info = reader.info();
        let (width, height) = (info.width as usize, info.height as usize);
        if info.bit_depth != png::BitDepth::One
            || info.color_type != png::ColorType::Grayscale
            || info.interlaced
        {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!(
                    "{:?} at {:?} bits{}",
                    info.color_type,
                    info.bit_depth,
                    if info.interlaced { ", interlaced" } else { "" }
                ),
                expected: "a 1-bit grey PNG, not interlaced (1 = land)",
            });
        }
        super::map_image::check_aspect(path, width, height)?;
        if width % TILE != 0 || height % TILE != 0 {
            return Err(MapError::Format {
                path: path.to_owned(),
                found: format!("{width} x {height}"),
                expected: "a land mask whose sides are multiples of 32 cells",
            });
        }
        let tiles_across = width / TILE;
        let mut tiles = Vec::with_capacity(tiles_across * height / TILE);
        let mut band = vec![[0u32; TILE]; tiles_across];
        for row in 0..height {
            let data = reader
                .next_row()
                .map_err(read_error)?
                .ok_or_else(|| read_error(png::DecodingError::LimitsExceeded))?
                .data();
            for (t, tile) in band.iter_mut().enumerate() {
                // 32 cells in 4 bytes, the first cell in the first byte's high bit.
                let b = &data[4 * t..4 * t + 4];
                let bits = u32::from_be_bytes([b[0], b[1], b[2], b[3]]).reverse_bits();
                tile[row % TILE] = bits;
            }
            if row % TILE == TILE - 1 {
                tiles.extend(band.iter().map(|rows| {
                    if rows.iter().all(|&r| r == 0) {
                        Tile::Sea
                    } else if rows.iter().all(|&r| r == u32::MAX) {
                        Tile::Land
                    } else {
                        Tile::Coast(Box::new(*rows))
                    }
                }));
            }
        }
        Ok(LandMask {
            width,
            height,
            tiles_across,
            tiles,
        })
    }

    /// Whether cell (column `i`, row `j`, row 0 at the north) is land.
    pub fn cell_is_land(&self, i: usize, j: usize) -> bool {
        match &self.tiles[(j / TILE) * self.tiles_across + i / TILE] {
            Tile::Sea => false,
            Tile::Land => true,
            Tile::Coast(rows) => rows[j % TILE] >> (i % TILE) & 1 == 1,
        }
    }

    /// Whether the cell holding a latitude and longitude (radians) is land.
    pub fn is_land(&self, lat_rad: f64, lon_rad: f64) -> bool {
        let taps = bilinear_taps(self.width, self.height, lat_rad, lon_rad);
        // The cell whose centre is nearest: the tap of largest weight.
        let (k, _) = taps
            .iter()
            .copied()
            .fold((0, -1.0), |best, t| if t.1 > best.1 { t } else { best });
        self.cell_is_land(k % self.width, k / self.width)
    }

    /// The land fraction at a latitude and longitude (radians), bilinear between cell
    /// centres: continuous, 1/2 on the coastline.
    pub fn land_fraction(&self, lat_rad: f64, lon_rad: f64) -> f64 {
        bilinear_taps(self.width, self.height, lat_rad, lon_rad)
            .iter()
            .filter(|&&(k, _)| self.cell_is_land(k % self.width, k / self.width))
            .map(|&(_, w)| w)
            .sum()
    }

    /// How many tiles the coast crosses (each holds 128 bytes of bits).
    pub fn coast_tiles(&self) -> usize {
        self.tiles
            .iter()
            .filter(|t| matches!(t, Tile::Coast(_)))
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1-bit PNG of `w x h` cells, land where `land(i, j)`.
    fn png_of(w: usize, h: usize, land: impl Fn(usize, usize) -> bool) -> Vec<u8> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, w as u32, h as u32);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::One);
        let mut writer = encoder.write_header().unwrap();
        let mut data = vec![0u8; w.div_ceil(8) * h];
        for j in 0..h {
            for i in 0..w {
                if land(i, j) {
                    data[j * w.div_ceil(8) + i / 8] |= 0x80 >> (i % 8);
                }
            }
        }
        writer.write_image_data(&data).unwrap();
        writer.finish().unwrap();
        out
    }

    #[test]
    fn cells_tiles_and_fractions_follow_the_bits() {
        let (w, h) = (128, 64);
        // Land west of column 45 in the northern half, and one single cell of land.
        let land = |i: usize, j: usize| (i < 45 && j < 32) || (i, j) == (100, 50);
        let mask = LandMask::decode(&png_of(w, h, land), Path::new("m.png")).unwrap();
        for j in 0..h {
            for i in 0..w {
                assert_eq!(mask.cell_is_land(i, j), land(i, j), "({i}, {j})");
            }
        }
        // Tiles: row 0 has land, land, coast, sea; row 1 sea, sea, sea, coast.
        assert_eq!(mask.coast_tiles(), 2);
        let centre = |i: usize, j: usize| {
            (
                (90.0 - (j as f64 + 0.5) * 180.0 / h as f64).to_radians(),
                (-180.0 + (i as f64 + 0.5) * 360.0 / w as f64).to_radians(),
            )
        };
        let (lat, lon) = centre(100, 50);
        assert!(mask.is_land(lat, lon));
        assert_eq!(mask.land_fraction(lat, lon), 1.0);
        // Halfway between the last land column and the first sea column: one half.
        let (lat, lon_a) = centre(44, 10);
        let (_, lon_b) = centre(45, 10);
        assert!((mask.land_fraction(lat, 0.5 * (lon_a + lon_b)) - 0.5).abs() < 1e-9);
    }

    #[test]
    fn a_mask_of_the_wrong_kind_is_named() {
        let mut grey = Vec::new();
        image::GrayImage::new(64, 32)
            .write_to(&mut Cursor::new(&mut grey), image::ImageFormat::Png)
            .unwrap();
        let e = LandMask::decode(&grey, Path::new("eight.png")).unwrap_err();
        assert!(
            e.to_string().contains("eight.png") && e.to_string().contains("1-bit"),
            "{e}"
        );
        let e = LandMask::decode(&png_of(48, 24, |_, _| true), Path::new("odd.png")).unwrap_err();
        assert!(e.to_string().contains("multiples of 32"), "{e}");
        let e = LandMask::decode(b"nothing", Path::new("junk.png")).unwrap_err();
        assert!(e.to_string().contains("junk.png"), "{e}");
    }
}
