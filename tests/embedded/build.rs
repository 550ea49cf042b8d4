//! Links the firmware with cortex-m-rt's `link.x`, which includes this crate's `memory.x`
//! (the board's memory map) from the linker's search path: both are passed here rather than
//! from a `.cargo/config.toml`, so that nothing outside this crate changes.

use std::env;
use std::fs;
use std::path::PathBuf;

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::write(out.join("memory.x"), include_bytes!("memory.x")).expect("OUT_DIR is writable");
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    println!("cargo:rerun-if-changed=build.rs");
    if env::var("TARGET").is_ok_and(|target| target.starts_with("thumb")) {
        // As cortex-m-quickstart: the sections need no page alignment on a microcontroller.
        println!("cargo:rustc-link-arg=--nmagic");
        println!("cargo:rustc-link-arg=-Tlink.x");
    }
}
