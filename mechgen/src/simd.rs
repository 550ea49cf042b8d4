//! Wider vector instructions for batch loops, chosen at run time.
//!
//! A build for x86-64's baseline may use only SSE2, whose registers hold 2 `f64` (4 `f32`):
//! a loop the compiler vectorises runs 2 lanes at a time even on a processor with AVX2 (4
//! `f64` lanes, and three-operand instructions that save the register copies SSE2 needs).
//! [`widest`] runs a closure compiled a second time for AVX2 and FMA where the processor
//! has them, and as built elsewhere, so one binary is both portable and fast. The scenes'
//! `*_batch` kernels run their loops through it.
//!
//! # The same results on every path
//!
//! The AVX2 copy is the same arithmetic in wider registers: Rust never contracts `a·b + c`
//! into a fused multiply-add (FMA is enabled only so that the copy may use it where code asks
//! for `mul_add`, which is rounded once either way), and every
//! operation the batch kernels use (`+ − × ÷`, `√`, `abs`, `copysign`, comparisons) is
//! correctly rounded or exact in SSE2 and AVX alike. So each path gives the same bits;
//! `tests/tests/simd.rs` checks it.

/// `f()`, compiled for AVX2 and FMA if this processor has them and the build does not
/// already assume them (`-C target-feature`), and as built otherwise (also without the
/// `std` feature, which the run-time check needs, and on other architectures).
///
/// For the wider copy to be the one that runs, `f`'s body must be inlined into it: mark the
/// closure `#[inline(always)]`, and every function it calls that should be vectorised
/// `#[inline(always)]` too (a call that is not inlined runs as built). The answer is the
/// same either way; only the speed differs.
///
/// ```
/// let angles = [0.1f64, 0.2, 0.3, 0.4];
/// let mut sines = [0.0; 4];
/// mechgen::simd::widest(
///     #[inline(always)]
///     || {
///         for (sine, &angle) in sines.iter_mut().zip(&angles) {
///             *sine = mechgen::fast::sin_cos(angle).0;
///         }
///     },
/// );
/// assert_eq!(sines[3], mechgen::fast::sin_cos(0.4).0);
/// ```
#[inline(always)]
pub fn widest<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(all(
        feature = "std",
        target_arch = "x86_64",
        not(all(target_feature = "avx2", target_feature = "fma"))
    ))]
    if avx2_fma() {
        // SAFETY: the processor has AVX2 and FMA (checked just above), which is all that
        // calling a function compiled with them requires.
        #[allow(unsafe_code)]
        return unsafe { x86::avx2_fma(f) };
    }
    f()
}

/// Whether [`widest`] runs its closure compiled for AVX2 and FMA: the processor has them
/// (`std`'s `is_x86_feature_detected!`, which detects once and caches the answer), or the
/// build assumes them; `false` without the `std` feature unless the build assumes them, and
/// on other architectures.
#[inline]
pub fn avx2_fma() -> bool {
    #[cfg(all(feature = "std", target_arch = "x86_64"))]
    {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }
    #[cfg(not(all(feature = "std", target_arch = "x86_64")))]
    {
        cfg!(all(target_feature = "avx2", target_feature = "fma"))
    }
}

#[cfg(all(
    feature = "std",
    target_arch = "x86_64",
    not(all(target_feature = "avx2", target_feature = "fma"))
))]
#[allow(unsafe_code)]
mod x86 {
    /// `f()` with AVX2 and FMA enabled, so that what is inlined into it may use them.
    ///
    /// # Safety
    ///
    /// The processor must support AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    pub(super) unsafe fn avx2_fma<R>(f: impl FnOnce() -> R) -> R {
        f()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_widest_path_runs_the_closure_once_and_returns_its_value() {
        let mut runs = 0;
        let value = widest(
            #[inline(always)]
            || {
                runs += 1;
                crate::fast::sin_cos(0.4f64)
            },
        );
        assert_eq!((runs, value), (1, crate::fast::sin_cos(0.4)));
        #[cfg(all(feature = "std", target_arch = "x86_64"))]
        assert_eq!(
            avx2_fma(),
            std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
        );
    }
}
