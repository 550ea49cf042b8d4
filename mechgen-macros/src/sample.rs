//! The numbers the macro's generic checks evaluate a declaration at (is a loop identically
//! zero, is the Jacobian singular at every position): a fixed sequence, so that the macro's
//! verdict is the same on every build and machine.

/// Numbers in [0, 1), the same sequence on every call (xorshift64, its top 53 bits).
pub(crate) fn fixed_sequence() -> impl FnMut() -> f64 {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    }
}
