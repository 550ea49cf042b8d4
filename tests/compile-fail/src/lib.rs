//! The compile-time diagnostics of `mechanism!`: the cases are in `ui/` and run by
//! `tests/ui.rs`. They live in a crate that depends on `mechgen` alone, because trybuild
//! builds every dependency of the crate it tests before it compiles the first case.
