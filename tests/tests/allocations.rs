//! Generated code never touches the heap: a counting global allocator sees no allocation
//! across position, velocity, acceleration and point calls.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

mod common;

use common::{example_1, inverted_slider_crank, slider_crank};
use mechanisms::{FourBarUnknowns, InvertedSliderCrankUnknowns, SliderCrankUnknowns};

/// Counts allocations made by the current thread (the test harness allocates on others).
struct CountingAllocator;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

// SAFETY: defers to the system allocator; the counter is a const-initialised thread-local
// `Cell`, which never allocates.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.with(|count| count.set(count.get() + 1));
        // SAFETY: same contract as ours.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as ours.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.with(|count| count.set(count.get() + 1));
        // SAFETY: same contract as ours.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: CountingAllocator = CountingAllocator;

fn allocations_during(work: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    work();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn the_counter_sees_an_allocation() {
    let count = allocations_during(|| drop(std::hint::black_box(Box::new(1))));
    assert_eq!(count, 1);
}

#[test]
fn kinematics_calls_do_not_allocate() {
    let options = mechgen::NewtonOptions::default();
    let count = allocations_during(|| {
        for degree in (0..360).step_by(15) {
            let theta2 = f64::from(degree).to_radians();

            let four_bar = example_1::<f64>();
            let near = four_bar.assemble(theta2, mechgen::Branch::Open).unwrap();
            let guess = FourBarUnknowns {
                theta3: near.theta3 + 0.05,
                theta4: near.theta4 - 0.05,
            };
            let q = four_bar.position(theta2, &guess, &options).unwrap().value;
            let v = four_bar.velocity(theta2, &q, 10.0).unwrap();
            let a = four_bar.acceleration(theta2, &q, 10.0, &v, 1.0).unwrap();
            four_bar.points(theta2, &q).unwrap();
            four_bar.point_velocities(theta2, &q, 10.0, &v).unwrap();
            four_bar
                .point_accelerations(theta2, &q, 10.0, &v, 1.0, &a)
                .unwrap();

            let slider = slider_crank::<f64>();
            let guess = SliderCrankUnknowns {
                theta3: 0.0,
                d: 190.0,
            };
            let q = slider.position(theta2, &guess, &options).unwrap().value;
            let v = slider.velocity(theta2, &q, 10.0).unwrap();
            slider.acceleration(theta2, &q, 10.0, &v, 1.0).unwrap();

            let inverted = inverted_slider_crank::<f64>();
            let guess = InvertedSliderCrankUnknowns {
                theta4: 3.0,
                b: 60.0,
            };
            let q = inverted.position(theta2, &guess, &options).unwrap().value;
            let v = inverted.velocity(theta2, &q, 10.0).unwrap();
            inverted.acceleration(theta2, &q, 10.0, &v, 1.0).unwrap();

            // Closed forms and a sweep of a few steps.
            let q = four_bar.assemble(theta2, mechgen::Branch::Open).unwrap();
            let sweep =
                mechgen::sweep::Sweep::new(&four_bar, theta2, q.to_array(), 0.01, 5, options);
            assert_eq!(sweep.filter(Result::is_ok).count(), 6);
            slider.assemble(theta2, mechgen::Branch::Crossed).unwrap();
            inverted.assemble(theta2, mechgen::Branch::Open).unwrap();

            // Errors are values too: a singular or non-finite case allocates nothing either.
            assert!(
                four_bar
                    .position(f64::NAN, &guess_four_bar(), &options)
                    .is_err()
            );
        }
    });
    assert_eq!(count, 0);
}

fn guess_four_bar() -> FourBarUnknowns<f64> {
    FourBarUnknowns {
        theta3: 0.4,
        theta4: 1.2,
    }
}
