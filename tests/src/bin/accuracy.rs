//! Prints the accuracy table: mechgen's errors against the 60-digit references, by distance
//! to the singular or special position, in f64 and f32, for positions, velocities and
//! accelerations. `cargo run -p mechgen-tests --bin accuracy > docs/ACCURACY.md`.

fn main() {
    print!("{}", mechgen_tests::reference::table());
}
