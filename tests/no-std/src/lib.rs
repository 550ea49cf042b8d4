//! A `#![no_std]` crate that declares mechanisms and uses their generated code, as firmware
//! would. CI builds it for a bare-metal target (`thumbv7em-none-eabihf`), which has no `std`
//! to fall back on, so anything in the generated code or the runtime that needs `std` or an
//! allocator fails the build.
//!
//! [`example1`] is the course notes' Example 1 four-bar, solved in f32 and f64 by generated
//! kernels and written out as text lines: the firmware in `tests/embedded` runs it on an
//! emulated Cortex-M4F and the host runs the same code (`examples/example1.rs`), and
//! `.ci/embedded` compares the two.
#![no_std]

use mechgen::{Error, NewtonOptions, mechanism};

mechanism! {
    /// A slider-crank with offset, as a controller would carry it.
    pub struct SliderCrank {
        params: pub l2, pub l3, pub c;
        input: theta2: angle;
        unknowns: theta3: angle, d: length;
        loop: l2 @ theta2 + l3 @ theta3 - c @ pi / 2 - d @ 0;
        point pin = d @ 0 + c @ pi / 2;
        generate: position, velocity, acceleration;
    }
}

mechanism! {
    /// A four-bar (KINEMATICS.md): ground `l1` from O2 = (0, 0) to O4 = (l1, 0), crank `l2`
    /// at the input `theta2`, coupler `l3` from A to B at `theta3`, rocker `l4` from O4 to B at
    /// `theta4`; the coupler point P is `a` from A at the angle `delta` from the coupler line.
    pub struct FourBar {
        params: pub l1, pub l2, pub l3, pub l4, pub a, pub delta: angle;
        input: theta2: angle;
        unknowns: theta3: angle, theta4: angle;
        loop: l2 @ theta2 + l3 @ theta3 - l4 @ theta4 - l1 @ 0;
        /// P, the coupler point.
        point coupler_point = l2 @ theta2 + a @ (theta3 + delta);
        generate: position, velocity, acceleration;
        /// The coupler's and rocker's angles, rates and accelerations.
        scene angles: theta3, theta4, theta3_dot, theta4_dot, theta3_ddot, theta4_ddot;
        /// The coupler point's position alone.
        scene coupler_path: coupler_point;
        /// The coupler point's position, velocity and acceleration.
        scene coupler_motion: coupler_point, coupler_point_dot, coupler_point_ddot;
    }
}

/// Slider position, velocity and acceleration at a crank angle, in f32, warm-started from
/// `previous`.
pub fn slider_state(
    linkage: &SliderCrank<f32>,
    theta2: f32,
    omega2: f32,
    previous: &SliderCrankUnknowns<f32>,
) -> Result<[f32; 3], Error<f32>> {
    let q = linkage
        .position(theta2, previous, &NewtonOptions::default())?
        .value;
    let v = linkage.velocity(theta2, &q, omega2)?;
    let a = linkage.acceleration(theta2, &q, omega2, &v, 0.0)?;
    let pin = linkage
        .point_accelerations(theta2, &q, omega2, &v, 0.0, &a)?
        .pin;
    Ok([q.d, v.d, pin.x])
}

/// The kernel calls: the only place [`example1`] (and the firmware's size table) calls
/// generated code, one small function per kernel.
///
/// Each is `#[inline(never)]`, so that in a release build it stays a function of its own
/// whose machine code can be measured (`tests/embedded/sizes.sh` reads the sizes of
/// `mechgen_no_std_check::kernels::<name>::<f32 or f64>` and of what it calls).
/// The general functions and the scene kernels (`scene_*`, on the [`FourBarScenes`] made
/// once per mechanism) are both here, so the size table can set them side by side.
///
/// [`FourBarScenes`]: crate::FourBarScenes
pub mod kernels {
    use mechgen::{Branch, Error, Motion, Real, Vec2};

    use crate::{
        FourBar, FourBarAngles, FourBarCouplerMotion, FourBarCouplerPath, FourBarPoints,
        FourBarScenes, FourBarUnknowns,
    };

    /// Scene kernel `angles`: θ3, θ4, their rates and accelerations, open branch.
    #[inline(never)]
    pub fn scene_angles<T: Real>(
        scenes: &FourBarScenes<T>,
        theta2: T,
        omega2: T,
        alpha2: T,
    ) -> Result<FourBarAngles<T>, Error<T>> {
        scenes.angles(theta2, Branch::Open, omega2, alpha2)
    }

    /// Scene kernel `coupler_path`: the coupler point's position, open branch.
    #[inline(never)]
    pub fn scene_coupler_path<T: Real>(
        scenes: &FourBarScenes<T>,
        theta2: T,
    ) -> Result<FourBarCouplerPath<T>, Error<T>> {
        scenes.coupler_path(theta2, Branch::Open)
    }

    /// Scene kernel `coupler_motion`: the coupler point's position, velocity and
    /// acceleration, open branch.
    #[inline(never)]
    pub fn scene_coupler_motion<T: Real>(
        scenes: &FourBarScenes<T>,
        theta2: T,
        omega2: T,
        alpha2: T,
    ) -> Result<FourBarCouplerMotion<T>, Error<T>> {
        scenes.coupler_motion(theta2, Branch::Open, omega2, alpha2)
    }

    /// Kernel `assemble`: the position in closed form, on the open branch.
    #[inline(never)]
    pub fn assemble<T: Real>(
        linkage: &FourBar<T>,
        theta2: T,
    ) -> Result<FourBarUnknowns<T>, Error<T>> {
        linkage.assemble(theta2, Branch::Open)
    }

    /// Kernel `motion`: position (open branch), rates and accelerations in one pass.
    #[inline(never)]
    pub fn motion<T: Real>(
        linkage: &FourBar<T>,
        theta2: T,
        omega2: T,
        alpha2: T,
    ) -> Result<Motion<FourBarUnknowns<T>, T>, Error<T>> {
        linkage.motion(theta2, Branch::Open, omega2, alpha2)
    }

    /// Kernel `points`: the tracked points' positions.
    #[inline(never)]
    pub fn points<T: Real>(
        linkage: &FourBar<T>,
        theta2: T,
        q: &FourBarUnknowns<T>,
    ) -> Result<FourBarPoints<Vec2<T>>, Error<T>> {
        linkage.points(theta2, q)
    }

    /// Kernel `point_velocities`: the tracked points' velocities.
    #[inline(never)]
    pub fn point_velocities<T: Real>(
        linkage: &FourBar<T>,
        theta2: T,
        q: &FourBarUnknowns<T>,
        omega2: T,
        v: &FourBarUnknowns<T>,
    ) -> Result<FourBarPoints<Vec2<T>>, Error<T>> {
        linkage.point_velocities(theta2, q, omega2, v)
    }

    /// Kernel `point_accelerations`: the tracked points' accelerations.
    #[inline(never)]
    pub fn point_accelerations<T: Real>(
        linkage: &FourBar<T>,
        theta2: T,
        q: &FourBarUnknowns<T>,
        omega2: T,
        v: &FourBarUnknowns<T>,
        alpha2: T,
        a: &FourBarUnknowns<T>,
    ) -> Result<FourBarPoints<Vec2<T>>, Error<T>> {
        linkage.point_accelerations(theta2, q, omega2, v, alpha2, a)
    }
}

/// The course notes' Example 1 (KINEMATICS.md): the four-bar 180/80/200/150 mm with the crank
/// at 60°, turning at 10 rad/s and speeding up at 5 rad/s², open branch, with a coupler point
/// 100 mm from A at 0.5 rad from the coupler line; solved by the generated kernels in f64 and
/// f32 and written as lines `<type> <kernel>.<quantity> <value>`, in SI-like units of the
/// notes (mm, rad, s).
///
/// Every value is written with enough digits to give back the exact binary number
/// (17 significant digits for f64, 9 for f32), so a comparison of two runs' lines compares
/// the numbers themselves; lines not starting with `f64 ` or `f32 ` are comments.
pub mod example1 {
    use core::fmt::{self, Write};
    use core::hint::black_box;

    use mechgen::{Error, Real, Vec2};

    use crate::{FourBar, kernels};

    /// Ground, crank, coupler, rocker (mm).
    pub const LENGTHS: [f64; 4] = [180.0, 80.0, 200.0, 150.0];
    /// The coupler point: distance from A (mm) and angle from the coupler line (rad).
    pub const COUPLER_POINT: (f64, f64) = (100.0, 0.5);
    /// The crank angle (degrees; the kernels take radians).
    pub const THETA2_DEGREES: f64 = 60.0;
    /// The crank's rate (rad/s).
    pub const OMEGA2: f64 = 10.0;
    /// The crank's acceleration (rad/s²).
    pub const ALPHA2: f64 = 5.0;

    /// The example's linkage at type `T`.
    pub fn linkage<T: Real>() -> FourBar<T> {
        let [l1, l2, l3, l4] = LENGTHS.map(T::constant);
        FourBar {
            l1,
            l2,
            l3,
            l4,
            a: T::constant(COUPLER_POINT.0),
            delta: T::constant(COUPLER_POINT.1),
        }
    }

    /// The crank angle in radians at type `T` (rounded once, from the f64 value).
    pub fn theta2<T: Real>() -> T {
        T::constant(THETA2_DEGREES.to_radians())
    }

    /// What can stop a run: a kernel's error, or the output refusing a line.
    #[derive(Debug)]
    pub enum Failure {
        /// An f64 kernel, named, returned an error.
        F64(&'static str, Error<f64>),
        /// An f32 kernel, named, returned an error.
        F32(&'static str, Error<f32>),
        /// The output could not be written.
        Write,
    }

    impl From<fmt::Error> for Failure {
        fn from(_: fmt::Error) -> Self {
            Failure::Write
        }
    }

    impl fmt::Display for Failure {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            match self {
                Failure::F64(kernel, error) => write!(f, "f64 kernel `{kernel}` failed: {error}"),
                Failure::F32(kernel, error) => write!(f, "f32 kernel `{kernel}` failed: {error}"),
                Failure::Write => f.write_str("could not write the output"),
            }
        }
    }

    /// A type the example runs at: its name in the lines and how its values are written.
    pub trait Scalar: Real {
        /// `f64` or `f32`.
        const NAME: &'static str;
        /// Writes the value with enough significant digits to round-trip.
        fn write_exact(self, out: &mut dyn Write) -> fmt::Result;
        /// A kernel's error as a [`Failure`].
        fn failure(kernel: &'static str) -> impl FnOnce(Error<Self>) -> Failure;
    }

    impl Scalar for f64 {
        const NAME: &'static str = "f64";
        fn write_exact(self, out: &mut dyn Write) -> fmt::Result {
            write!(out, "{self:.16e}")
        }
        fn failure(kernel: &'static str) -> impl FnOnce(Error<Self>) -> Failure {
            move |error| Failure::F64(kernel, error)
        }
    }

    impl Scalar for f32 {
        const NAME: &'static str = "f32";
        fn write_exact(self, out: &mut dyn Write) -> fmt::Result {
            write!(out, "{self:.8e}")
        }
        fn failure(kernel: &'static str) -> impl FnOnce(Error<Self>) -> Failure {
            move |error| Failure::F32(kernel, error)
        }
    }

    /// Writes `<type> <name><suffix> <value>`.
    fn line<T: Scalar>(out: &mut dyn Write, name: &str, suffix: &str, value: T) -> fmt::Result {
        write!(out, "{} {name}{suffix} ", T::NAME)?;
        value.write_exact(out)?;
        out.write_char('\n')
    }

    /// Writes a vector's two lines, `<name>.x` and `<name>.y`.
    fn vector<T: Scalar>(out: &mut dyn Write, name: &str, value: Vec2<T>) -> fmt::Result {
        line(out, name, ".x", value.x)?;
        line(out, name, ".y", value.y)
    }

    /// Solves the example at type `T` with the generated kernels and writes its lines.
    pub fn run<T: Scalar>(out: &mut dyn Write) -> Result<(), Failure> {
        // Opaque to the optimiser, so that no kernel is specialised for these constants (the
        // firmware's size table measures the kernels as any caller would get them).
        let linkage = black_box(linkage::<T>());
        let theta2 = black_box(theta2::<T>());
        let (omega2, alpha2) = black_box((T::constant(OMEGA2), T::constant(ALPHA2)));

        let q = kernels::assemble(&linkage, theta2).map_err(T::failure("assemble"))?;
        line(out, "assemble.theta3", "", q.theta3)?;
        line(out, "assemble.theta4", "", q.theta4)?;

        let m = kernels::motion(&linkage, theta2, omega2, alpha2).map_err(T::failure("motion"))?;
        line(out, "motion.theta3", "", m.position.theta3)?;
        line(out, "motion.theta4", "", m.position.theta4)?;
        line(out, "motion.theta3_dot", "", m.velocity.theta3)?;
        line(out, "motion.theta4_dot", "", m.velocity.theta4)?;
        line(out, "motion.theta3_ddot", "", m.acceleration.theta3)?;
        line(out, "motion.theta4_ddot", "", m.acceleration.theta4)?;

        let (q, v, a) = (m.position, m.velocity, m.acceleration);
        let p = kernels::points(&linkage, theta2, &q).map_err(T::failure("points"))?;
        vector(out, "points.coupler_point", p.coupler_point)?;
        let p = kernels::point_velocities(&linkage, theta2, &q, omega2, &v)
            .map_err(T::failure("point_velocities"))?;
        vector(out, "point_velocities.coupler_point", p.coupler_point)?;
        let p = kernels::point_accelerations(&linkage, theta2, &q, omega2, &v, alpha2, &a)
            .map_err(T::failure("point_accelerations"))?;
        vector(out, "point_accelerations.coupler_point", p.coupler_point)?;

        let scenes = linkage.scenes().map_err(T::failure("scenes"))?;
        let s = kernels::scene_angles(&scenes, theta2, omega2, alpha2)
            .map_err(T::failure("scene_angles"))?;
        line(out, "scene_angles.theta3", "", s.theta3)?;
        line(out, "scene_angles.theta4", "", s.theta4)?;
        line(out, "scene_angles.theta3_dot", "", s.theta3_dot)?;
        line(out, "scene_angles.theta4_dot", "", s.theta4_dot)?;
        line(out, "scene_angles.theta3_ddot", "", s.theta3_ddot)?;
        line(out, "scene_angles.theta4_ddot", "", s.theta4_ddot)?;
        let s = kernels::scene_coupler_path(&scenes, theta2)
            .map_err(T::failure("scene_coupler_path"))?;
        vector(out, "scene_coupler_path.coupler_point", s.coupler_point)?;
        let s = kernels::scene_coupler_motion(&scenes, theta2, omega2, alpha2)
            .map_err(T::failure("scene_coupler_motion"))?;
        vector(out, "scene_coupler_motion.coupler_point", s.coupler_point)?;
        vector(
            out,
            "scene_coupler_motion.coupler_point_dot",
            s.coupler_point_dot,
        )?;
        vector(
            out,
            "scene_coupler_motion.coupler_point_ddot",
            s.coupler_point_ddot,
        )?;
        Ok(())
    }

    /// The whole example: f64, then f32.
    pub fn run_all(out: &mut dyn Write) -> Result<(), Failure> {
        run::<f64>(out)?;
        run::<f32>(out)
    }
}
