#!/usr/bin/env bash
# Checks that mechgen-macros, mechgen and mechanisms can be published: packages the three
# and builds each from its package alone, as crates.io would, without uploading anything.
# None of them is on crates.io yet and each depends on the one before, so they go through
# one multi-package dry run (cargo 1.90 or later), which resolves them against a local
# registry of the packages it just made. It needs the crates.io index (network).
# Extra arguments go to cargo, e.g. `--allow-dirty` to try uncommitted changes.
set -euo pipefail
cd "$(dirname "$0")/.."
# The members that are not published (tests, compile-fail, no-std, no-panic) say
# `publish = false`, and `--workspace` leaves them out.
cargo publish --dry-run --workspace "$@"
# Again with every feature, so that mechgen's optional `nalgebra` module builds from its
# package too.
cargo publish --dry-run --workspace --all-features "$@"
