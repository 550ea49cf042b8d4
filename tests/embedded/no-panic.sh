#!/usr/bin/env bash
# No panic path in the firmware's generated kernels: disassembles the firmware (an ELF built
# by .ci/embedded) and fails if any function reachable from a generated kernel
# (mechgen_no_std_check::kernels::*) by direct calls or tail calls has `panic` in its name.
# The machine-code counterpart, on the embedded target itself, of tests/no-panic (which proves
# the same on the host for every kernel of the shipped mechanisms).
#
#   tests/embedded/no-panic.sh <ELF>
set -euo pipefail
elf="$1"

# shellcheck source=tools.sh
source "$(dirname "$0")/tools.sh" no-panic.sh

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# Function symbols: mangled, then demangled (same order: -p does not sort).
"${nm[@]}" -p --defined-only "$elf" | awk '$2 ~ /^[tTwW]$/ { print $3 }' >"$work/mangled"
"${nm[@]}" -p --defined-only -C "$elf" | awk '$2 ~ /^[tTwW]$/ { $1 = $2 = ""; sub(/^ +/, ""); print }' >"$work/demangled"
paste "$work/mangled" "$work/demangled" >"$work/symbols"
# Direct calls and branches to other functions: "caller<TAB>callee" (mangled).
"${objdump[@]}" -d --no-show-raw-insn "$elf" | awk '
    match($0, /^[0-9a-f]+ <[^>]+>:$/) { current = substr($0, index($0, "<") + 1); sub(/>:$/, "", current); next }
    /\t(bl|blx|b|b\.w|b\.n)\t/ && match($0, /<[^>+]+(\+0x[0-9a-f]+)?>/) {
        callee = substr($0, RSTART + 1, RLENGTH - 2); sub(/\+0x[0-9a-f]+$/, "", callee)
        if (callee != current) print current "\t" callee
    }' | sort -u >"$work/calls"

awk -F'\t' '
    FNR == 1 { file++ }
    file == 1 { name[$1] = $2; if ($2 ~ /^mechgen_no_std_check::kernels::/) roots[$1] = 1; next }
    file == 2 { edges[$1] = edges[$1] " " $2; next }
    END {
        for (root in roots) {
            kernels++
            delete from; delete queue; from[root] = ""; queue[1] = root; n = 1
            for (i = 1; i <= n; i++) {
                split(edges[queue[i]], callees, " ")
                for (j in callees) {
                    c = callees[j]
                    if (c == "" || (c in from)) continue
                    from[c] = queue[i]; queue[++n] = c
                    if (name[c] ~ /panic/) {
                        path = name[c]
                        for (p = from[c]; p != ""; p = from[p]) path = name[p] " -> " path
                        print "PANIC PATH: " path
                        bad++
                    }
                }
            }
            reached += n - 1
        }
        if (kernels == 0) { print "no-panic.sh: no generated kernel found in the firmware"; exit 1 }
        if (bad) exit 1
        printf "no panic path: %d generated kernels, %d function visits, none reaching a function named *panic*\n", kernels, reached
    }' "$work/symbols" "$work/calls"
