#!/usr/bin/env bash
# The seeded tests (proptest's, and the edge tests, which take proptest's seed) under seeds 1
# to N (12 unless given), outside CI, which keeps one seed. Prints each seed's failing tests.
# A failing property test writes its case into a *.proptest-regressions file; every such file
# is put back after each seed, so a run leaves no regression behind, false or not.
#
#   bash tests/seeds.sh [N]
set -uo pipefail
cd "$(dirname "$0")/.."
seeds=${1:-12}
# The test binaries that draw from the seed.
targets=(-p mechgen-tests --test closed_forms --test edges --test edges_analyses
    --test edges_solvers --test jacobians --test scenes --test stability)
export INSTA_UPDATE=no
cargo test -q "${targets[@]}" --no-run
restore() {
    git ls-files -z '*.proptest-regressions' | xargs -0 -r git checkout -q --
    git ls-files -z --others --exclude-standard '*.proptest-regressions' | xargs -0 -r rm -f
}
for seed in $(seq 1 "$seeds"); do
    failed=$(PROPTEST_RNG_SEED=$seed cargo test -q "${targets[@]}" --no-fail-fast 2>&1 |
        sed -n 's/^    \([A-Za-z_0-9:]*\)$/\1/p' | sort -u | tr '\n' ' ')
    restore
    echo "seed $seed: ${failed:-every test passes}"
done
