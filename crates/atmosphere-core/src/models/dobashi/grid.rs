//! A 2D table of f32 texels with one channel per wavelength (an RGB texture for three
//! wavelengths), read by linear interpolation between nodes: the layout of every dobashi
//! table, so that the GPU binds each as one 2D texture.

/// Nodes (i, j) at integer coordinates x = i in [0, width - 1], y = j in [0, height - 1].
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    pub width: usize,
    pub height: usize,
    pub channels: usize,
    /// Row-major: node (i, j) holds `channels` values from `(j * width + i) * channels`.
    pub data: Vec<f32>,
}

impl Grid {
    /// A grid filled with `value`.
    pub fn filled(width: usize, height: usize, channels: usize, value: f32) -> Grid {
        Grid {
            width,
            height,
            channels,
            data: vec![value; width * height * channels],
        }
    }

    /// Bytes of the texels.
    pub fn bytes(&self) -> usize {
        std::mem::size_of_val(self.data.as_slice())
    }

    /// Sets node (i, j) from f64 values (rounded to f32).
    pub fn set(&mut self, i: usize, j: usize, values: &[f64]) {
        let start = (j * self.width + i) * self.channels;
        for (d, v) in self.data[start..start + self.channels]
            .iter_mut()
            .zip(values)
        {
            *d = *v as f32;
        }
    }

    /// The stored values of node (i, j).
    pub fn node(&self, i: usize, j: usize) -> &[f32] {
        let start = (j * self.width + i) * self.channels;
        &self.data[start..start + self.channels]
    }

    /// Bilinear interpolation at (x, y), each clamped to the grid, into `out`.
    pub fn sample(&self, x: f64, y: f64, out: &mut [f64]) {
        let (i, ax) = Self::cell(x, self.width);
        let (j, ay) = Self::cell(y, self.height);
        let (i1, j1) = ((i + 1).min(self.width - 1), (j + 1).min(self.height - 1));
        let (a, b) = (self.node(i, j), self.node(i1, j));
        let (c, d) = (self.node(i, j1), self.node(i1, j1));
        for k in 0..self.channels {
            let low = a[k] as f64 + ax * (b[k] as f64 - a[k] as f64);
            let high = c[k] as f64 + ax * (d[k] as f64 - c[k] as f64);
            out[k] = low + ay * (high - low);
        }
    }

    /// The node below `x` (clamped to the axis) and the weight of the next one.
    fn cell(x: f64, size: usize) -> (usize, f64) {
        let x = if x.is_nan() {
            0.0
        } else {
            x.clamp(0.0, (size - 1) as f64)
        };
        let i = (x.floor() as usize).min(size.saturating_sub(2));
        (i, (x - i as f64).min(1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_between_nodes_and_clamps_outside() {
        let mut g = Grid::filled(3, 2, 2, 0.0);
        g.set(0, 0, &[0.0, 10.0]);
        g.set(1, 0, &[1.0, 20.0]);
        g.set(0, 1, &[2.0, 30.0]);
        g.set(1, 1, &[3.0, 40.0]);
        let mut out = [0.0; 2];
        g.sample(0.5, 0.5, &mut out);
        assert_eq!(out, [1.5, 25.0]);
        g.sample(-3.0, 9.0, &mut out);
        assert_eq!(out, [2.0, 30.0]);
        g.sample(2.0, 0.0, &mut out);
        assert_eq!(out, [0.0, 0.0]);
        assert_eq!(g.bytes(), 3 * 2 * 2 * 4);
    }
}
