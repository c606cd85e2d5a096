//! The seeded random numbers of the checks and the benchmarks (SplitMix64): every run draws the
//! same cases. Written by hand: a dozen lines, where a crate would add a dependency for them.

use nalgebra::Matrix3;

/// SplitMix64: a seeded generator, so every run checks (and times) the same cases.
pub struct Rng(pub u64);

impl Rng {
    /// The next draw, uniform in [0, 1) (an infinite stream, not an `Iterator`).
    #[allow(clippy::should_implement_trait)]
    pub fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A draw uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
    /// A random symmetric positive-definite matrix L L^T, diagonal of L in `diag`, the rest in
    /// (-off, off).
    pub fn spd(&mut self, diag: (f64, f64), off: f64) -> Matrix3<f64> {
        let l = Matrix3::new(
            self.range(diag.0, diag.1),
            0.0,
            0.0,
            self.range(-off, off),
            self.range(diag.0, diag.1),
            0.0,
            self.range(-off, off),
            self.range(-off, off),
            self.range(diag.0, diag.1),
        );
        l * l.transpose()
    }
}
