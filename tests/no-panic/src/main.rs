//! No generated kernel can panic: a link-time proof.
//!
//! Every kernel the macro generates for the shipped mechanisms (`mechanisms`: `FourBar`,
//! `SliderCrank`, `InvertedSliderCrank`, `WattSixBar`, `StephensonSixBar`, `JansenLeg`), in
//! f64 and f32, is wrapped in a function marked with dtolnay's [`no_panic`]: the attribute
//! puts a guard in the function whose destructor, run only while unwinding out of it, calls a
//! symbol that does not exist. If the optimiser cannot prove that no panic (a bounds check, an
//! `unwrap`, an overflow, a panicking callee) is reachable from the function, that call stays
//! and the build fails to link, naming the function. So the check is the build itself:
//!
//! ```sh
//! tests/no-panic/check.sh     # what CI runs: the builds below, and the canary
//! cargo build --profile no-panic -p mechgen-no-panic-check                 # libm, as no_std
//! cargo build --profile no-panic -p mechgen-no-panic-check --features std  # platform maths
//! CARGO_PROFILE_NO_PANIC_OPT_LEVEL=z cargo build --profile no-panic -p mechgen-no-panic-check
//! ```
//!
//! The `no-panic` profile (the workspace's Cargo.toml) is release with fat LTO and one codegen
//! unit: the optimiser must see into every callee, libm's included, to know it cannot unwind;
//! with several codegen units or crates, a call it cannot see into counts as a possible panic
//! and the verdict would depend on how the code happened to be split. The check passes at
//! opt-level 3 (the profile's), 2, "s" and "z". At 1 the optimiser does not even remove the
//! guard from `residual`, which has nothing that can panic: the attribute cannot judge there
//! (the disassembly at 1 shows no panic reachable from any wrapper). It needs `panic =
//! "unwind"` too (with `abort` nothing unwinds and every function would pass: the canary,
//! `--features canary`, shows the check is not vacuous), so it runs on the host, not on the
//! embedded target. Running the binary lists what was checked.

use core::hint::black_box;

use mechanisms::{
    FourBar, FourBarPoints, FourBarSensitivities, FourBarUnknowns, InvertedSliderCrank,
    InvertedSliderCrankPoints, InvertedSliderCrankUnknowns, JansenLeg, JansenLegPoints,
    JansenLegUnknowns, SliderCrank, SliderCrankPoints, SliderCrankUnknowns, StephensonSixBar,
    StephensonSixBarPoints, StephensonSixBarUnknowns, WattSixBar, WattSixBarPoints,
    WattSixBarSensitivities, WattSixBarUnknowns,
};
use mechgen::{AccelerationParts, Branch, Error, Motion, NewtonOptions, Solved, Vec2};
#[cfg(not(debug_assertions))]
use no_panic::no_panic;

/// Checked wrappers, by name, with their addresses (taken so that each is compiled and linked).
type Kernels = Vec<(&'static str, *const ())>;
/// A mechanism at one type, and its wrappers.
type Module = (&'static str, fn() -> Kernels);

/// Wraps one mechanism's kernels at one scalar type in a module of `#[no_panic]` functions,
/// and lists them (name and address, so each is compiled and linked) in `kernels()`.
/// `closed:` adds the closed-form kernels (`assemble`, `motion`, `branch_of`) with their branch
/// type; `sensitivities:` adds `sensitivities` and `point_sensitivities` with theirs.
macro_rules! check {
    (
        $module:ident: $mech:ident<$t:ty>, $unknowns:ident, $points:ident, $n:literal
        $(, closed: $branches:ty)?
        $(, sensitivities: $sensitivities:ident)?
    ) => {
        mod $module {
            use super::*;

            type T = $t;
            type U = $unknowns<T>;

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn residual(m: &$mech<T>, input: T, q: &U) -> [T; $n] {
                m.residual(input, q)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn jacobian(m: &$mech<T>, input: T, q: &U) -> [[T; $n]; $n] {
                m.jacobian(input, q)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn input_jacobian(m: &$mech<T>, input: T, q: &U) -> [T; $n] {
                m.input_jacobian(input, q)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn condition(m: &$mech<T>, input: T, q: &U) -> T {
                m.condition(input, q)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn position(
                m: &$mech<T>,
                input: T,
                guess: &U,
                options: &NewtonOptions<T>,
            ) -> Result<Solved<U, T>, Error<T>> {
                m.position(input, guess, options)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn velocity(m: &$mech<T>, input: T, q: &U, rate: T) -> Result<U, Error<T>> {
                m.velocity(input, q, rate)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn acceleration(
                m: &$mech<T>,
                input: T,
                q: &U,
                rate: T,
                v: &U,
                acceleration: T,
            ) -> Result<U, Error<T>> {
                m.acceleration(input, q, rate, v, acceleration)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn motion_at(
                m: &$mech<T>,
                input: T,
                q: &U,
                rate: T,
                acceleration: T,
            ) -> Result<Motion<U, T>, Error<T>> {
                m.motion_at(input, q, rate, acceleration)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn points(m: &$mech<T>, input: T, q: &U) -> Result<$points<Vec2<T>>, Error<T>> {
                m.points(input, q)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn point_velocities(
                m: &$mech<T>,
                input: T,
                q: &U,
                rate: T,
                v: &U,
            ) -> Result<$points<Vec2<T>>, Error<T>> {
                m.point_velocities(input, q, rate, v)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn point_accelerations(
                m: &$mech<T>,
                input: T,
                q: &U,
                rate: T,
                v: &U,
                acceleration: T,
                a: &U,
            ) -> Result<$points<Vec2<T>>, Error<T>> {
                m.point_accelerations(input, q, rate, v, acceleration, a)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn point_acceleration_parts(
                m: &$mech<T>,
                input: T,
                q: &U,
                rate: T,
                v: &U,
                acceleration: T,
                a: &U,
            ) -> Result<$points<AccelerationParts<T>>, Error<T>> {
                m.point_acceleration_parts(input, q, rate, v, acceleration, a)
            }

            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn motion_near(
                m: &$mech<T>,
                input: T,
                guess: &U,
                options: &NewtonOptions<T>,
                rate: T,
                acceleration: T,
            ) -> Result<Solved<Motion<U, T>, T>, Error<T>> {
                m.motion_near(input, guess, options, rate, acceleration)
            }

            /// `newton()`, then its `motion_near`: the prepared solver's constructor and
            /// its inlined common path.
            #[cfg_attr(not(debug_assertions), no_panic)]
            #[inline(never)]
            pub fn newton_motion_near(
                m: &$mech<T>,
                input: T,
                guess: &U,
                options: &NewtonOptions<T>,
                rate: T,
                acceleration: T,
            ) -> Result<Solved<Motion<U, T>, T>, Error<T>> {
                m.newton()?.motion_near(input, guess, options, rate, acceleration)
            }

            $(
                #[cfg_attr(not(debug_assertions), no_panic)]
                #[inline(never)]
                pub fn assemble(m: &$mech<T>, input: T, branch: $branches) -> Result<U, Error<T>> {
                    m.assemble(input, branch)
                }

                #[cfg_attr(not(debug_assertions), no_panic)]
                #[inline(never)]
                pub fn branch_of(m: &$mech<T>, input: T, q: &U) -> $branches {
                    m.branch_of(input, q)
                }

                #[cfg_attr(not(debug_assertions), no_panic)]
                #[inline(never)]
                pub fn motion(
                    m: &$mech<T>,
                    input: T,
                    branch: $branches,
                    rate: T,
                    acceleration: T,
                ) -> Result<Motion<U, T>, Error<T>> {
                    m.motion(input, branch, rate, acceleration)
                }
            )?

            $(
                #[cfg_attr(not(debug_assertions), no_panic)]
                #[inline(never)]
                pub fn sensitivities(m: &$mech<T>, input: T, q: &U) -> Result<$sensitivities<U>, Error<T>> {
                    m.sensitivities(input, q)
                }

                #[cfg_attr(not(debug_assertions), no_panic)]
                #[inline(never)]
                pub fn point_sensitivities(
                    m: &$mech<T>,
                    input: T,
                    q: &U,
                ) -> Result<$sensitivities<$points<Vec2<T>>>, Error<T>> {
                    m.point_sensitivities(input, q)
                }
            )?

            /// Every wrapper's name and address.
            pub fn kernels() -> Kernels {
                #[allow(unused_mut)]
                let mut list: Kernels = vec![
                    ("residual", residual as *const ()),
                    ("jacobian", jacobian as *const ()),
                    ("input_jacobian", input_jacobian as *const ()),
                    ("condition", condition as *const ()),
                    ("position", position as *const ()),
                    ("velocity", velocity as *const ()),
                    ("acceleration", acceleration as *const ()),
                    ("motion_at", motion_at as *const ()),
                    ("motion_near", motion_near as *const ()),
                    ("newton_motion_near", newton_motion_near as *const ()),
                    ("points", points as *const ()),
                    ("point_velocities", point_velocities as *const ()),
                    ("point_accelerations", point_accelerations as *const ()),
                    ("point_acceleration_parts", point_acceleration_parts as *const ()),
                ];
                $(
                    // (Names the branch type only so that this part repeats with `closed:`.)
                    let _: Option<$branches> = None;
                    list.push(("assemble", assemble as *const ()));
                    list.push(("branch_of", branch_of as *const ()));
                    list.push(("motion", motion as *const ()));
                )?
                $(
                    let _: Option<$sensitivities<()>> = None;
                    list.push(("sensitivities", sensitivities as *const ()));
                    list.push(("point_sensitivities", point_sensitivities as *const ()));
                )?
                list
            }
        }
    };
}

check!(
    four_bar_f64: FourBar<f64>, FourBarUnknowns, FourBarPoints, 2, closed: Branch,
    sensitivities: FourBarSensitivities
);
check!(
    four_bar_f32: FourBar<f32>, FourBarUnknowns, FourBarPoints, 2, closed: Branch,
    sensitivities: FourBarSensitivities
);
check!(slider_crank_f64: SliderCrank<f64>, SliderCrankUnknowns, SliderCrankPoints, 2, closed: Branch);
check!(slider_crank_f32: SliderCrank<f32>, SliderCrankUnknowns, SliderCrankPoints, 2, closed: Branch);
check!(
    inverted_slider_crank_f64: InvertedSliderCrank<f64>,
    InvertedSliderCrankUnknowns, InvertedSliderCrankPoints, 2, closed: Branch
);
check!(
    inverted_slider_crank_f32: InvertedSliderCrank<f32>,
    InvertedSliderCrankUnknowns, InvertedSliderCrankPoints, 2, closed: Branch
);
check!(
    watt_six_bar_f64: WattSixBar<f64>, WattSixBarUnknowns, WattSixBarPoints, 4,
    closed: [Branch; 2], sensitivities: WattSixBarSensitivities
);
check!(
    watt_six_bar_f32: WattSixBar<f32>, WattSixBarUnknowns, WattSixBarPoints, 4,
    closed: [Branch; 2], sensitivities: WattSixBarSensitivities
);
check!(
    stephenson_six_bar_f64: StephensonSixBar<f64>,
    StephensonSixBarUnknowns, StephensonSixBarPoints, 4
);
check!(
    stephenson_six_bar_f32: StephensonSixBar<f32>,
    StephensonSixBarUnknowns, StephensonSixBarPoints, 4
);
check!(jansen_leg_f64: JansenLeg<f64>, JansenLegUnknowns, JansenLegPoints, 6, closed: [Branch; 3]);
check!(jansen_leg_f32: JansenLeg<f32>, JansenLegUnknowns, JansenLegPoints, 6, closed: [Branch; 3]);

/// Wraps one scene kernel (or the `scenes()` that makes them) as a `#[no_panic]` function.
macro_rules! scene {
    ($name:ident($receiver:ty $(, $arg:ident: $ty:ty)*) -> $out:ty = $method:ident) => {
        #[cfg_attr(not(debug_assertions), no_panic)]
        #[inline(never)]
        pub fn $name(receiver: &$receiver $(, $arg: $ty)*) -> Result<$out, Error<T>> {
            receiver.$method($($arg),*)
        }
    };
}

/// The shipped mechanisms' scene kernels, and the `scenes()` that make them, at one type.
macro_rules! check_scenes {
    ($module:ident: $t:ty) => {
        mod $module {
            use super::*;
            use mechanisms::{
                FourBarAngles, FourBarCouplerMotion, FourBarCouplerPath, FourBarScenes,
                InvertedSliderCrankScenes, InvertedSliderCrankState, JansenLegFootMotion,
                JansenLegFootPath, JansenLegScenes, SliderCrankScenes, SliderCrankSlider,
                SliderCrankState, WattSixBarOutput, WattSixBarScenes,
            };

            type T = $t;

            scene!(four_bar_scenes(FourBar<T>) -> FourBarScenes<T> = scenes);
            scene!(four_bar_angles(FourBarScenes<T>, input: T, branch: Branch, rate: T, acceleration: T) -> FourBarAngles<T> = angles);
            scene!(four_bar_coupler_path(FourBarScenes<T>, input: T, branch: Branch) -> FourBarCouplerPath<T> = coupler_path);
            scene!(four_bar_coupler_motion(FourBarScenes<T>, input: T, branch: Branch, rate: T, acceleration: T) -> FourBarCouplerMotion<T> = coupler_motion);
            scene!(slider_crank_scenes(SliderCrank<T>) -> SliderCrankScenes<T> = scenes);
            scene!(slider_crank_state(SliderCrankScenes<T>, input: T, branch: Branch, rate: T, acceleration: T) -> SliderCrankState<T> = state);
            scene!(slider_crank_slider(SliderCrankScenes<T>, input: T, branch: Branch, rate: T, acceleration: T) -> SliderCrankSlider<T> = slider);
            scene!(inverted_slider_crank_scenes(InvertedSliderCrank<T>) -> InvertedSliderCrankScenes<T> = scenes);
            scene!(inverted_slider_crank_state(InvertedSliderCrankScenes<T>, input: T, branch: Branch, rate: T, acceleration: T) -> InvertedSliderCrankState<T> = state);
            scene!(watt_six_bar_scenes(WattSixBar<T>) -> WattSixBarScenes<T> = scenes);
            scene!(watt_six_bar_output(WattSixBarScenes<T>, input: T, branches: [Branch; 2], rate: T, acceleration: T) -> WattSixBarOutput<T> = output);
            scene!(jansen_leg_scenes(JansenLeg<T>) -> JansenLegScenes<T> = scenes);
            scene!(jansen_leg_foot_path(JansenLegScenes<T>, input: T, branches: [Branch; 3]) -> JansenLegFootPath<T> = foot_path);
            scene!(jansen_leg_foot_motion(JansenLegScenes<T>, input: T, branches: [Branch; 3], rate: T, acceleration: T) -> JansenLegFootMotion<T> = foot_motion);

            /// Every wrapper's name and address.
            pub fn kernels() -> Kernels {
                vec![
                    ("FourBar::scenes", four_bar_scenes as *const ()),
                    ("FourBarScenes::angles", four_bar_angles as *const ()),
                    ("FourBarScenes::coupler_path", four_bar_coupler_path as *const ()),
                    ("FourBarScenes::coupler_motion", four_bar_coupler_motion as *const ()),
                    ("SliderCrank::scenes", slider_crank_scenes as *const ()),
                    ("SliderCrankScenes::state", slider_crank_state as *const ()),
                    ("SliderCrankScenes::slider", slider_crank_slider as *const ()),
                    ("InvertedSliderCrank::scenes", inverted_slider_crank_scenes as *const ()),
                    ("InvertedSliderCrankScenes::state", inverted_slider_crank_state as *const ()),
                    ("WattSixBar::scenes", watt_six_bar_scenes as *const ()),
                    ("WattSixBarScenes::output", watt_six_bar_output as *const ()),
                    ("JansenLeg::scenes", jansen_leg_scenes as *const ()),
                    ("JansenLegScenes::foot_path", jansen_leg_foot_path as *const ()),
                    ("JansenLegScenes::foot_motion", jansen_leg_foot_motion as *const ()),
                ]
            }
        }
    };
}

check_scenes!(scenes_f64: f64);
check_scenes!(scenes_f32: f32);

/// The canary (`--features canary`): a function that can panic, an unchecked index, so that
/// the build must fail to link. `check.sh` builds it to show that the check has teeth (it
/// would pass everything with `panic = "abort"`, say, or without optimisation).
#[cfg(feature = "canary")]
#[cfg_attr(not(debug_assertions), no_panic)]
#[inline(never)]
pub fn canary(values: &[f64], index: usize) -> f64 {
    values[index]
}

fn main() {
    #[cfg(feature = "canary")]
    black_box(canary as *const ());

    let modules: [Module; 14] = [
        ("FourBar<f64>", four_bar_f64::kernels),
        ("FourBar<f32>", four_bar_f32::kernels),
        ("SliderCrank<f64>", slider_crank_f64::kernels),
        ("SliderCrank<f32>", slider_crank_f32::kernels),
        (
            "InvertedSliderCrank<f64>",
            inverted_slider_crank_f64::kernels,
        ),
        (
            "InvertedSliderCrank<f32>",
            inverted_slider_crank_f32::kernels,
        ),
        ("WattSixBar<f64>", watt_six_bar_f64::kernels),
        ("WattSixBar<f32>", watt_six_bar_f32::kernels),
        ("StephensonSixBar<f64>", stephenson_six_bar_f64::kernels),
        ("StephensonSixBar<f32>", stephenson_six_bar_f32::kernels),
        ("JansenLeg<f64>", jansen_leg_f64::kernels),
        ("JansenLeg<f32>", jansen_leg_f32::kernels),
        ("scene kernels <f64>", scenes_f64::kernels),
        ("scene kernels <f32>", scenes_f32::kernels),
    ];
    let mut total = 0;
    for (mechanism, kernels) in modules {
        let kernels = kernels();
        let names: Vec<&str> = kernels
            .iter()
            .map(|&(name, address)| {
                black_box(address);
                name
            })
            .collect();
        total += names.len();
        println!("{mechanism}: {}", names.join(", "));
    }
    let mode = if cfg!(debug_assertions) {
        "NOT checked (a debug build: build with --release)"
    } else {
        "each linked with #[no_panic]: none can panic"
    };
    println!("{total} generated kernels, {mode}");
}
