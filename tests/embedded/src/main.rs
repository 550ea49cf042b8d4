//! Firmware for an emulated Cortex-M4F: QEMU's `mps2-an386` board, run by `.ci/embedded`.
//!
//! It solves the course notes' Example 1 four-bar with the generated kernels in f64 and f32
//! ([`mechgen_no_std_check::example1`], the same code the host runs), writes the values over
//! semihosting, checks the hand-written kernels ([`hand`]) against the generated ones, and
//! exits through semihosting: status 0 if every kernel succeeded and agreed, 1 otherwise
//! (a panic too). Lines starting with `#` are comments; `.ci/embedded` compares the others
//! with the host's.
//!
//! ```sh
//! cargo build --release --target thumbv7em-none-eabihf --manifest-path tests/embedded/Cargo.toml
//! qemu-system-arm -machine mps2-an386 -cpu cortex-m4 -nographic \
//!     -semihosting-config enable=on,target=native -kernel <the ELF>
//! ```
#![no_std]
#![no_main]

#[cfg(not(all(target_arch = "arm", target_os = "none")))]
compile_error!(
    "mechgen-embedded is firmware: build it with `--target thumbv7em-none-eabihf` (see .ci/embedded)"
);

mod hand;

use core::fmt::{self, Write};
use core::hint::black_box;
use core::panic::PanicInfo;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hio};
use mechgen::Vec2;
use mechgen_no_std_check::example1::{self, Scalar};
use mechgen_no_std_check::{FourBar, kernels};

/// How far the hand-written kernels may be from the generated ones, relative to each value:
/// they use other formulas (Norton's), so they agree to rounding, amplified by the
/// example's condition, not bit for bit.
const HAND_RELATIVE_F64: f64 = 1e-12;
const HAND_RELATIVE_F32: f64 = 1e-5;

/// The host's console, through semihosting.
struct Console(hio::HostStream);

impl Write for Console {
    fn write_str(&mut self, text: &str) -> fmt::Result {
        self.0.write_all(text.as_bytes()).map_err(|()| fmt::Error)
    }
}

/// The hand-written kernels' results beside the generated ones', as pairs of values.
fn hand_against_generated<T: Scalar>() -> Option<[(T, T); 18]> {
    // Opaque inputs, as in `example1::run`: no kernel is specialised for them.
    let generated: FourBar<T> = black_box(example1::linkage());
    let linkage = hand::Linkage {
        l1: generated.l1,
        l2: generated.l2,
        l3: generated.l3,
        l4: generated.l4,
        a: generated.a,
        delta: generated.delta,
    };
    let theta2 = black_box(example1::theta2::<T>());
    let (omega2, alpha2) =
        black_box((T::constant(example1::OMEGA2), T::constant(example1::ALPHA2)));

    let m = kernels::motion(&generated, theta2, omega2, alpha2).ok()?;
    let (q, v, a) = (m.position, m.velocity, m.acceleration);
    let p = kernels::points(&generated, theta2, &q).ok()?.coupler_point;
    let pv = kernels::point_velocities(&generated, theta2, &q, omega2, &v)
        .ok()?
        .coupler_point;
    let pa = kernels::point_accelerations(&generated, theta2, &q, omega2, &v, alpha2, &a)
        .ok()?
        .coupler_point;

    let position = hand::position(&linkage, theta2)?;
    let [hq, hv, ha] = hand::motion(&linkage, theta2, omega2, alpha2)?;
    let hp = hand::coupler_point(&linkage, theta2, hq[0]);
    let hpv = hand::coupler_point_velocity(&linkage, theta2, omega2, hq[0], hv[0]);
    let hpa =
        hand::coupler_point_acceleration(&linkage, theta2, [omega2, alpha2], hq[0], [hv[0], ha[0]]);
    // The scene kernels against the hand-written kernels that compute the same.
    let scenes = generated.scenes().ok()?;
    let path = kernels::scene_coupler_path(&scenes, theta2).ok()?.coupler_point;
    let moving = kernels::scene_coupler_motion(&scenes, theta2, omega2, alpha2).ok()?;
    let angles = kernels::scene_angles(&scenes, theta2, omega2, alpha2).ok()?;
    let hand_path = hand::coupler_path(&linkage, theta2)?;
    let [_, _, hand_acceleration] = hand::coupler_motion(&linkage, theta2, omega2, alpha2)?;

    let pair = |g: Vec2<T>, h: Vec2<T>| [(g.x, h.x), (g.y, h.y)];
    let [p0, p1] = pair(p, hp);
    let [v0, v1] = pair(pv, hpv);
    let [a0, a1] = pair(pa, hpa);
    let [s0, s1] = pair(path, hand_path);
    let [m0, m1] = pair(moving.coupler_point_ddot, hand_acceleration);
    Some([
        (angles.theta3_ddot, ha[0]),
        (angles.theta4_dot, hv[1]),
        s0,
        s1,
        m0,
        m1,
        (q.theta3, position[0]),
        (q.theta4, position[1]),
        (v.theta3, hv[0]),
        (v.theta4, hv[1]),
        (a.theta3, ha[0]),
        (a.theta4, ha[1]),
        p0,
        p1,
        v0,
        v1,
        a0,
        a1,
    ])
}

/// Checks the hand-written kernels against the generated ones at `T`; writes the largest
/// relative difference and returns whether it is within `allowed`.
fn check_hand<T: Scalar + fmt::LowerExp>(
    out: &mut Console,
    allowed: f64,
) -> Result<bool, fmt::Error> {
    let Some(pairs) = hand_against_generated::<T>() else {
        writeln!(out, "# hand-written {}: a kernel failed", T::NAME)?;
        return Ok(false);
    };
    let mut largest = T::zero();
    for (generated, hand) in pairs {
        let scale = generated.abs().max(hand.abs());
        if generated != hand {
            let relative = (generated - hand).abs() / scale;
            // NaN counts as the largest difference.
            if relative.is_nan() || relative > largest {
                largest = relative;
            }
        }
    }
    let within = largest <= T::constant(allowed);
    writeln!(
        out,
        "# hand-written kernels agree with the generated ones at {}: largest relative difference {largest:.1e} over {} values (allowed {allowed:.0e}){}",
        T::NAME,
        pairs.len(),
        if within { "" } else { "  <-- MISMATCH" },
    )?;
    Ok(within)
}

fn run(out: &mut Console) -> Result<bool, fmt::Error> {
    writeln!(
        out,
        "# mechgen-embedded: the course notes' Example 1 four-bar on a Cortex-M4F (QEMU mps2-an386)"
    )?;
    // cortex-m-rt's reset handler turns the FPU on for an `eabihf` target.
    let fpu = cortex_m::peripheral::SCB::fpu_access_mode();
    writeln!(out, "# FPU access: {fpu:?}")?;
    let mut ok = match example1::run_all(out) {
        Ok(()) => true,
        Err(failure) => {
            writeln!(out, "# FAILED: {failure}")?;
            false
        }
    };
    ok &= check_hand::<f64>(out, HAND_RELATIVE_F64)?;
    ok &= check_hand::<f32>(out, HAND_RELATIVE_F32)?;
    Ok(ok)
}

#[entry]
fn main() -> ! {
    let ok = match hio::hstdout() {
        Ok(stream) => run(&mut Console(stream)).unwrap_or(false),
        Err(()) => false,
    };
    debug::exit(if ok {
        debug::EXIT_SUCCESS
    } else {
        debug::EXIT_FAILURE
    });
    // Semihosting's exit does not return under QEMU; on a debugger that ignores it, stop here.
    cortex_m::asm::udf()
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    if let Ok(stream) = hio::hstderr() {
        let _ = writeln!(Console(stream), "# PANIC: {info}");
    }
    debug::exit(debug::EXIT_FAILURE);
    cortex_m::asm::udf()
}
