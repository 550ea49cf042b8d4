//! The one random generator the crate draws from (Monte Carlo tolerance samples, synthesis
//! starts): seeded, so that every draw can be repeated.

use mechgen::Real;

/// Steele, Lea and Flood's SplitMix64: a small, well-mixed generator, enough for sampling.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    pub(crate) fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1]: 53 random bits (never 0, which a logarithm takes).
    pub(crate) fn unit(&mut self) -> f64 {
        ((self.next() >> 11) + 1) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [0, 1): all 64 bits, rounded. (Synthesis's starts; it needs `std`.)
    #[cfg_attr(not(feature = "std"), allow(dead_code))]
    pub(crate) fn fraction(&mut self) -> f64 {
        // 2^64, exactly.
        self.next() as f64 / 18_446_744_073_709_551_616.0
    }

    /// A standard normal deviate (Box–Muller).
    pub(crate) fn normal<T: Real>(&mut self) -> T {
        let (u, v) = (self.unit(), self.unit());
        let (u, v) = (T::constant(u), T::constant(v));
        (T::constant(-2.0) * u.ln()).sqrt() * (T::constant(core::f64::consts::TAU) * v).cos()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// SplitMix64's published outputs from the seed 0 (Vigna's `splitmix64.c`), and the
    /// uniform, fraction and normal deviates from the seed 7 as a Python transcription of
    /// these formulas gives them (the integers exactly, the normals to its libm).
    #[test]
    fn draws_are_splitmix64_s() {
        let mut random = SplitMix64(0);
        assert_eq!(
            [random.next(), random.next(), random.next()],
            [
                0xE220_A839_7B1D_CDAF,
                0x6E78_9E6A_A1B9_65F4,
                0x06C4_5D18_8009_454F
            ]
        );
        let mut random = SplitMix64(7);
        assert_eq!(random.unit(), 0.389_829_748_391_271_6);
        assert_eq!(random.fraction(), 0.016_788_294_528_156_195);
        for want in [-0.396_523_975_253_817_7, 0.004_498_526_159_831_252_5] {
            let normal: f64 = random.normal();
            assert!(
                (normal - want).abs() <= 4.0 * f64::EPSILON,
                "{normal} != {want}"
            );
        }
    }
}
