#!/usr/bin/env bash
# No generated kernel of the shipped mechanisms can panic: builds mechgen-no-panic-check,
# whose every wrapper is #[no_panic] (the link fails if one can panic), with the `no-panic`
# profile (release, fat LTO, one codegen unit) at opt-level 3, "s" and "z" with libm (as in
# no_std), and at 3 with the platform's maths (std); then builds its canary, a function that
# can panic, and fails unless that build fails, so that the check cannot pass vacuously.
set -euo pipefail
cd "$(dirname "$0")/../.."

build() {
    echo "== no-panic: cargo build --profile no-panic -p mechgen-no-panic-check $* (opt-level ${CARGO_PROFILE_NO_PANIC_OPT_LEVEL:-3})"
    cargo build --quiet --profile no-panic -p mechgen-no-panic-check "$@"
}

for level in 3 s z; do
    CARGO_PROFILE_NO_PANIC_OPT_LEVEL=$level build
done
build --features std
"${CARGO_TARGET_DIR:-target}/no-panic/mechgen-no-panic-check"

echo "== no-panic: the canary, which can panic, must fail to link"
if cargo build --quiet --profile no-panic -p mechgen-no-panic-check --features canary 2>"${TMPDIR:-/tmp}/no-panic-canary.log"; then
    echo "FAILED: the canary linked, so the no-panic check proves nothing" >&2
    exit 1
fi
if ! grep -q 'detected panic in function `canary`' "${TMPDIR:-/tmp}/no-panic-canary.log"; then
    cat "${TMPDIR:-/tmp}/no-panic-canary.log" >&2
    echo "FAILED: the canary's build failed, but not for its panic" >&2
    exit 1
fi
echo "the canary failed to link, as it must: the check has teeth"
