#!/usr/bin/env bash
# Code size of each generated four-bar kernel beside a hand-written equivalent, on
# thumbv7em-none-eabihf (Cortex-M4F), as a markdown table on stdout (for docs/PERFORMANCE.md).
#
#   tests/embedded/sizes.sh            # opt-level "s" (the firmware's profile) and 3
#   tests/embedded/sizes.sh s          # one optimisation level
#
# What is measured: the firmware in this directory (release: fat LTO, one codegen unit),
# whose kernels are `#[inline(never)]` functions with stable names, generic over the scalar
# and named with v0 mangling so that f32 and f64 differ:
#   generated    mechgen_no_std_check::kernels::<kernel>::<f32|f64>
#   hand-written mechgen_embedded::hand::<kernel>::<f32|f64>
# For each, from the symbol table (llvm-nm -S) and the disassembly (llvm-objdump -d):
#   own      the function's own .text bytes;
#   callees  every function it reaches by direct calls and tail calls (bl, b, b.w), each
#            counted once, except the maths library (libm's sin/cos/atan2/sqrt) and the
#            compiler's soft-float routines (f64 on an FPU that only has single precision),
#            which are shared by every kernel and by any other floating-point code;
#   maths    those shared routines (with fmax, integer division and the like from
#            compiler-builtins), reported apart.
# Builds into $CARGO_TARGET_DIR (default: the repository's target/). Needs llvm-nm and
# llvm-objdump: rustup's llvm-tools (installed here if missing), else binutils-arm-none-eabi.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
target=thumbv7em-none-eabihf
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
levels=("$@")
[ ${#levels[@]} -gt 0 ] || levels=(s 3)

# --- tools -----------------------------------------------------------------------------
# shellcheck source=tools.sh
source "$here/tools.sh" sizes.sh
rustup target list --installed | grep -qx "$target" || rustup target add "$target" >&2

# kernel label | generated function | hand-written function
rows=(
    "position, closed form (open branch)|assemble|position"
    "position, rates and accelerations|motion|motion"
    "coupler point position|points|coupler_point"
    "coupler point velocity|point_velocities|coupler_point_velocity"
    "coupler point acceleration|point_accelerations|coupler_point_acceleration"
    "scene: angles, rates and accelerations|scene_angles|motion"
    "scene: coupler point position|scene_coupler_path|coupler_path"
    "scene: coupler point position, velocity, acceleration|scene_coupler_motion|coupler_motion"
)

# Prints "own callees maths|callee names" (bytes; the names of the non-maths callees) for the function whose demangled name is $2, in the
# call graph of the ELF whose listings are in $1 (symbols.txt, calls.txt).
measure() {
    awk -v want="$2" -F'\t' '
        FNR == 1 { file++ }
        # symbols.txt: address, size, mangled name, demangled name
        file == 1 {
            size[$3] = $2 + 0; addr[$3] = $1; demangled[$3] = $4
            if ($4 == want) start = $3
            next
        }
        # calls.txt: caller, callee (mangled)
        file == 2 { edges[$1] = edges[$1] " " $2; next }
        END {
            if (start == "") { print "missing"; exit }
            own = size[start]; seen[start] = 1; queue[1] = start; n = 1
            for (i = 1; i <= n; i++) {
                split(edges[queue[i]], next_, " ")
                for (j in next_) {
                    callee = next_[j]
                    if (callee == "" || (callee in seen) || !(callee in size)) continue
                    seen[callee] = 1; queue[++n] = callee
                }
            }
            for (f in seen) {
                if (f == start || (addr[f] in counted)) continue
                counted[addr[f]] = 1
                d = demangled[f]
                if (d ~ /^libm::/ || d ~ /compiler_builtins/ || d ~ /^__(aeabi_|udiv|[a-z]+[sd]f[0-9])/ || d ~ /^f(max|min)f?$/)
                    maths += size[f]
                else {
                    callees += size[f]
                    # The unit separator: demangled names hold spaces, commas and
                    # semicolons (`<[T; 3]>::try_map`).
                    names = names (names == "" ? "" : "\037") d
                }
            }
            printf "%d %d %d|%s\n", own, callees, maths, names
        }' "$1/symbols.txt" "$1/calls.txt"
}

# The callee names `measure` prints (joined by the unit separator), sorted, each in
# backticks (as code, so that markdown keeps their `<…>`), joined by commas.
listed() {
    tr '\037' '\n' <<<"$1" | sort | awk 'NF { printf "%s`%s`", (n++ ? ", " : ""), $0 }'
}

for level in "${levels[@]}"; do
    CARGO_PROFILE_RELEASE_OPT_LEVEL="$level" \
        RUSTFLAGS="${RUSTFLAGS:-} -C symbol-mangling-version=v0" \
        cargo build --quiet --release --target "$target" --manifest-path "$here/Cargo.toml" >&2
    elf="$CARGO_TARGET_DIR/$target/release/mechgen-embedded"
    work="$(mktemp -d)"
    trap 'rm -rf "$work"' EXIT
    # Function symbols, mangled and demangled (same order: -p does not sort).
    "${nm[@]}" -p -S -t d --defined-only "$elf" | awk '$3 ~ /^[tTwW]$/ { print $1 "\t" $2 "\t" $4 }' >"$work/mangled"
    "${nm[@]}" -p -S -t d --defined-only -C "$elf" | awk '$3 ~ /^[tTwW]$/ { $1 = $2 = $3 = ""; sub(/^ +/, ""); print }' >"$work/demangled"
    paste "$work/mangled" "$work/demangled" >"$work/symbols.txt"
    # Direct calls and branches to other functions: "caller<TAB>callee".
    "${objdump[@]}" -d --no-show-raw-insn "$elf" | awk '
        match($0, /^[0-9a-f]+ <[^>]+>:$/) { current = substr($0, index($0, "<") + 1); sub(/>:$/, "", current); next }
        /\t(bl|blx|b|b\.w|b\.n)\t/ && match($0, /<[^>+]+(\+0x[0-9a-f]+)?>/) {
            callee = substr($0, RSTART + 1, RLENGTH - 2); sub(/\+0x[0-9a-f]+$/, "", callee)
            if (callee != current) print current "\t" callee
        }' | sort -u >"$work/calls.txt"
    text="$("${nm[@]}" -S -t d --defined-only "$elf" | awk '$3 ~ /^[tTwW]$/ { s += $2 } END { print s }')"

    echo
    echo "### thumbv7em-none-eabihf, opt-level $level (fat LTO, one codegen unit): .text bytes"
    echo
    echo "Each cell: the kernel's own code + what it calls = total; maths: libm, soft-float and other"
    echo "compiler-builtins routines it reaches, shared by all floating-point code and counted apart."
    echo
    callee_notes=()
    echo "| kernel | type | generated | maths | hand-written | maths | generated / hand-written |"
    echo "|---|---|---|---|---|---|---|"
    for scalar in f64 f32; do
        for row in "${rows[@]}"; do
            IFS='|' read -r label generated hand <<<"$row"
            g="mechgen_no_std_check::kernels::$generated::<$scalar>"
            h="mechgen_embedded::hand::$hand::<$scalar>"
            IFS='|' read -r g_sizes g_names <<<"$(measure "$work" "$g")"
            IFS='|' read -r h_sizes h_names <<<"$(measure "$work" "$h")"
            g_names="$(listed "$g_names")"
            h_names="$(listed "$h_names")"
            read -r g_own g_callees g_maths <<<"$g_sizes"
            read -r h_own h_callees h_maths <<<"$h_sizes"
            if [ "$g_own" = missing ] || [ "$h_own" = missing ]; then
                echo "sizes.sh: no symbol $g or $h in $elf (inlined or renamed?)" >&2
                exit 1
            fi
            g_total=$((g_own + g_callees)) h_total=$((h_own + h_callees))
            ratio="$(awk -v g="$g_total" -v h="$h_total" 'BEGIN { printf "%.2f×", g / h }')"
            printf '| %s | %s | `%s` %d + %d = **%d** | %d | `%s` %d + %d = **%d** | %d | %s |\n' \
                "$label" "$scalar" "$generated" "$g_own" "$g_callees" "$g_total" "$g_maths" \
                "$hand" "$h_own" "$h_callees" "$h_total" "$h_maths" "$ratio"
            [ -z "$g_names" ] || callee_notes+=("\`$generated::<$scalar>\` calls $g_names")
            [ -z "$h_names" ] || callee_notes+=("hand-written \`$hand::<$scalar>\` calls $h_names")
        done
    done
    echo
    echo "Callees (besides the maths):"
    echo
    for note in "${callee_notes[@]}"; do
        echo "- $note"
    done
    echo
    echo "The whole firmware (both types, formatting, semihosting): $text bytes of functions."
    rm -rf "$work"
    trap - EXIT
done
