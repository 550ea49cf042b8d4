#!/usr/bin/env bash
# Mutation testing of the runtime and of the shipped mechanisms' analyses with cargo-mutants,
# and docs/MUTANTS.md from its results.
#
# Each run's results (mutants.out/, not kept) go into tests/mutants-record.tsv, which is: one
# row per file, of the commit the file was last run at, and its survivors. A run of some files
# replaces their rows and keeps the others', so a change to one file needs a run of that file
# alone; the report marks a row whose file has changed since its commit.
#
#   bash tests/mutants.sh                      every file in FILES below, then the report
#   bash tests/mutants.sh FILE...              only these files (earlier results replaced)
#   bash tests/mutants.sh --iterate [FILE...]  only the mutants not yet caught (or unviable)
#                                              in the earlier results, which it adds to
#   bash tests/mutants.sh --from N FILE...     only each file's mutants from the Nth on, in
#                                              cargo-mutants' order (`--list`): the rest of
#                                              a run cut short (earlier results replaced;
#                                              with --iterate, added to)
#   bash tests/mutants.sh --report             the report alone, from the record (and the
#                                              results in mutants.out/ not yet recorded)
#
# Each mutant is built and tested against the kill-set of its crate (`kill_set` below). For the
# runtime, `cargo test -p mechgen`: its unit tests and doctests, a few seconds a mutant. For the
# shipped analyses, `cargo test -p mechanisms`: the library's unit tests and doctests and the
# command-line program's end-to-end tests (mechanisms/tests/), 13 s after a change to one file
# (measured on the two shared cores), well under a minute, so the tests are not filtered by
# name. The integration tests (tests/tests/) would kill more, but at minutes a mutant; a
# solver's mistakes should be caught by the fast tests beside it. Survivors that no test can
# kill are explained in tests/mutants-equivalent.txt, which the report merges in. Slow (most of
# an hour for the runtime's files on two cores, longer for the shipped analyses'), so not in CI.
set -euo pipefail
cd "$(dirname "$0")/.."

VERSION=27.1.0
TOOLS=.tools
OUT=mutants.out
EXPLAINED=tests/mutants-equivalent.txt
REPORT=docs/MUTANTS.md
RECORD=tests/mutants-record.tsv

# The files run, in order of importance: closed forms, the scene kernels' checked steps, the
# branch-free maths, the sines and cosines of angle sums and rate limits, the linear solves, Newton; the runtime's analyses; its
# scalar type, accuracy estimates, branches, errors and vectors; the sweep; the wider
# instructions' choice and nalgebra's conversions (with its feature); then the shipped
# mechanisms' analyses.
FILES=(
    mechgen/src/closed.rs
    mechgen/src/kernel.rs
    mechgen/src/fast.rs
    mechgen/src/angle_sum.rs
    mechgen/src/rate_limits.rs
    mechgen/src/linear.rs
    mechgen/src/newton.rs
    mechgen/src/grashof.rs
    mechgen/src/advantage.rs
    mechgen/src/real.rs
    mechgen/src/accuracy.rs
    mechgen/src/branch.rs
    mechgen/src/error.rs
    mechgen/src/vec2.rs
    mechgen/src/sweep.rs
    mechgen/src/simd.rs
    mechgen/src/nalgebra_support.rs
    mechanisms/src/five_bar.rs
    mechanisms/src/triangle.rs
    mechanisms/src/sums.rs
    mechanisms/src/tolerance.rs
    mechanisms/src/four_bar.rs
    mechanisms/src/slider_crank.rs
    mechanisms/src/dimensions.rs
    mechanisms/src/random.rs
    mechanisms/src/synthesis/fit.rs
    mechanisms/src/synthesis/mod.rs
)

# The files of `mechanisms/` that hold analyses (what the report counts as the shipped
# analyses, run or not); the rest declare the mechanisms (`mechanism!` and constructors) or
# are the command-line program.
ANALYSES=(
    mechanisms/src/five_bar.rs
    mechanisms/src/triangle.rs
    mechanisms/src/sums.rs
    mechanisms/src/tolerance.rs
    mechanisms/src/four_bar.rs
    mechanisms/src/slider_crank.rs
    mechanisms/src/dimensions.rs
    mechanisms/src/random.rs
    mechanisms/src/synthesis/mod.rs
    mechanisms/src/synthesis/fit.rs
)

mutants() { "$TOOLS/bin/cargo-mutants" mutants "$@"; }

# The directory under mutants.out/ of one file's results: the runtime's by the file's stem
# (`closed`), the shipped mechanisms' prefixed with `mechanisms-` and their path under src/
# (`mechanisms-four_bar`, `mechanisms-synthesis-fit`), so no two files share one.
stem() {
    case $1 in
        mechgen/src/*) basename "$1" .rs ;;
        mechanisms/src/*) local rest=${1#mechanisms/src/}; echo "mechanisms-${rest%.rs}" | tr / - ;;
        *) echo "not a file this script mutates: $1" >&2; exit 1 ;;
    esac
}

# The cargo-mutants options that choose the tests a mutant of one file must fail.
kill_set() {
    case $1 in
        # Compiled only with its feature, and tested by its doctests.
        mechgen/src/nalgebra_support.rs) echo --test-package mechgen --features nalgebra ;;
        mechgen/*) echo --test-package mechgen ;;
        mechanisms/*) echo --test-package mechanisms ;;
    esac
}

install() {
    if [ "$("$TOOLS/bin/cargo-mutants" mutants --version 2>/dev/null)" != "cargo-mutants $VERSION" ]; then
        cargo install --locked --root "$TOOLS" "cargo-mutants@$VERSION"
    fi
}

# One cargo-mutants run per file, each into mutants.out/<file's stem>/, so a file can be run
# again alone. Missed mutants make cargo-mutants exit non-zero: that is a result, not a failure.
# The whole list of a file's mutants is kept beside its results (all.txt), so the report can
# tell the mutants not run (with --from) from those that no longer exist.
run() {
    local file stem status results commit files=("$@")
    for file in "${files[@]}"; do
        stem=$(stem "$file")
        results="$OUT/$stem/mutants.out"
        if [ "$ITERATE" = 1 ] && [ -d "$results" ]; then
            # cargo-mutants carries the caught forward (previously_caught.txt) but not the
            # unviable, which it skips too: kept aside here, and added back after.
            cp "$results/unviable.txt" "$OUT/$stem/unviable.before"
            set -- --iterate
        else
            rm -rf "${OUT:?}/$stem"
            mkdir -p "$OUT/$stem"
            : > "$OUT/$stem/unviable.before"
            set --
        fi
        mutants --list --file "$file" > "$OUT/$stem/all.txt"
        if [ "$FROM" -gt 1 ]; then
            # Each later mutant by its whole name, which is what --re matches. (cargo-mutants
            # 27.1.0 lets the deletion of a struct expression's field through any --re, so such
            # a mutant before the Nth is run too; the report says which were.)
            set -- "$@" --re "^($(tail -n +"$FROM" "$OUT/$stem/all.txt" |
                sed 's/[][\\.*+?(){}|^$]/\\&/g' | paste -sd '|'))\$"
        fi
        status=0
        # The commit of the tree cargo-mutants copies now (a commit made while it runs is not
        # in its copy).
        commit=$(stamp)
        # shellcheck disable=SC2046 # the kill-set's options, split into words
        mutants "$@" --file "$file" $(kill_set "$file") --jobs 1 --minimum-test-timeout 30 \
            --no-times --colors never --output "$OUT/$stem" || status=$?
        # 0: all caught; 2: some missed; 3: some timed out. Anything else is cargo-mutants failing.
        case $status in 0 | 2 | 3) ;; *) echo "cargo-mutants failed on $file ($status)" >&2; exit "$status" ;; esac
        echo "$commit" > "$OUT/$stem/commit"
        rm -f "$OUT/$stem/recorded"
        sort -u "$OUT/$stem/unviable.before" "$results/unviable.txt" -o "$results/unviable.txt"
    done
}

# The results of one outcome (caught, missed, unviable, timeout) for one file.
outcome() { cat "$OUT/$1/mutants.out/$2.txt" 2>/dev/null || true; }

# Every mutant of one file that was tested, whatever its outcome.
tested() {
    local kind
    for kind in caught previously_caught missed unviable timeout; do outcome "$1" "$kind"; done | sort -u
}

# Of the whole list of one file's mutants (all.txt, in cargo-mutants' order), the positions of
# those tested, as ranges (`1–139`), or nothing where the list is missing (an older run).
positions() {
    [ -f "$OUT/$1/all.txt" ] || return 0
    awk 'NR == FNR { tested[$0] = 1; next }
        ($0 in tested) {
            if (first && FNR != last + 1) { out = out sep range(); sep = ", "; first = 0 }
            if (!first) first = FNR
            last = FNR
        }
        function range() { return first == last ? first : first "–" last }
        END { if (first) out = out sep range(); print out }' <(tested "$1") "$OUT/$1/all.txt"
}

# The explanation recorded for a survivor, or nothing: in $EXPLAINED, a survivor is a line as
# cargo-mutants prints it (`path:line:column: mutation`), its explanation the indented lines
# under it (several survivors may share one).
explanation() {
    awk -v key="$1" '
        /^#/ || /^$/ { next }
        /^[^ ]/ { if (found && text != "") exit; found = found || ($0 == key); next }
        found { sub(/^ +/, ""); text = text (text == "" ? "" : " ") $0 }
        END { print text }
    ' "$EXPLAINED"
}

# HEAD's short hash, with `-dirty` where mechgen/ or mechanisms/ differ from it: what a file's
# results are of, written beside them when the file is run.
stamp() {
    local hash
    hash=$(git rev-parse --short HEAD)
    if git diff --quiet HEAD -- mechgen mechanisms; then echo "$hash"; else echo "$hash-dirty"; fi
}

# One file's fresh results (mutants.out/) into the record: its row and survivors replace the
# record's, so the record keeps every file's last run, whichever runs came since.
record_file() {
    local file=$1 stem caught missed unviable timeout total whole part="" commit
    stem=$(stem "$file")
    # An iterated run lists the unviable among the previously caught.
    caught=$( (outcome "$stem" caught; outcome "$stem" previously_caught) | sort -u |
        grep -vxF -f <(outcome "$stem" unviable; echo) | grep -c . || true)
    missed=$(outcome "$stem" missed | grep -c . || true)
    unviable=$(outcome "$stem" unviable | grep -c . || true)
    timeout=$(outcome "$stem" timeout | grep -c . || true)
    total=$((caught + missed + unviable + timeout))
    whole=$(grep -c . "$OUT/$stem/all.txt" 2>/dev/null) || whole=$total
    if [ "$total" -lt "$whole" ]; then
        part="$(positions "$stem") of $whole"
    fi
    # Results from before the script wrote their commit: HEAD's, as the report said then.
    commit=$(cat "$OUT/$stem/commit" 2>/dev/null || stamp)
    {
        awk -F '\t' -v file="$file" '
            ($1 == "row" && $2 == file) || ($1 == "survivor" && index($2, file ":") == 1) { next }
            { print }' "$RECORD"
        printf 'row\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$file" "$commit" "$total" "$caught" \
            "$missed" "$unviable" "$timeout" "$part"
        outcome "$stem" missed | grep . | sed 's/^/survivor\t/' || true
    } > "$RECORD.new"
    # Rows in the order of the report's files, each file's survivors after the rows.
    {
        grep '^#' "$RECORD.new" || true
        for f in mechgen/src/*.rs "${ANALYSES[@]}"; do
            awk -F '\t' -v file="$f" '$1 == "row" && $2 == file' "$RECORD.new"
        done
        for f in mechgen/src/*.rs "${ANALYSES[@]}"; do
            awk -F '\t' -v file="$f" '$1 == "survivor" && index($2, file ":") == 1' "$RECORD.new"
        done
    } > "$RECORD"
    rm "$RECORD.new"
}

# The record's fields for one file's row: commit, mutants, caught, missed, unviable, timeout,
# part (tab-separated), or nothing if the file was never run.
recorded() { awk -F '\t' -v file="$1" '$1 == "row" && $2 == file { print; exit }' "$RECORD" | cut -f3-; }

report() {
    local file stem commit total caught missed unviable timeout part line why changed
    local partial=() not_tested=() changed_since=()
    local run_files=() not_run=() not_run_analyses=() no_mutants=() survivors=() equivalent=0
    local not_killed=0 unexplained=0
    # Fresh results first: a file run since the last report replaces its record, once (so
    # that results left in mutants.out/ never overwrite a record made since, elsewhere).
    for file in mechgen/src/*.rs "${ANALYSES[@]}"; do
        stem=$(stem "$file")
        if [ -f "$OUT/$stem/mutants.out/outcomes.json" ] && [ ! -f "$OUT/$stem/recorded" ]; then
            record_file "$file"
            touch "$OUT/$stem/recorded"
        fi
    done
    for file in mechgen/src/*.rs "${ANALYSES[@]}"; do
        if [ -n "$(recorded "$file")" ]; then
            run_files+=("$file")
        elif [ -z "$(mutants --list --file "$file" 2>/dev/null)" ]; then
            no_mutants+=("$file")
        elif [[ $file == mechgen/* ]]; then
            not_run+=("$file")
        else
            not_run_analyses+=("$file")
        fi
    done
    mapfile -t survivors < <(awk -F '\t' '$1 == "survivor" { print $2 }' "$RECORD")
    {
        echo "# Mutation testing"
        echo
        echo "Written by \`bash tests/mutants.sh\` (cargo-mutants $VERSION, installed into"
        echo "\`$TOOLS/\` by the script) from the results it keeps in"
        echo "[\`$RECORD\`](../$RECORD), a file at a time: each file's row is of the commit it"
        echo "names, the last at which the script ran that file (a commit marked -dirty had"
        echo "uncommitted changes to mechgen or mechanisms). Do not edit: explanations of"
        echo "survivors live in [\`$EXPLAINED\`](../$EXPLAINED)."
        echo
        echo "Each mutant (a change cargo-mutants makes to one operator, comparison or function"
        echo "body) is built and tested against its own crate's fast tests: a mutant of the"
        echo "runtime (\`mechgen/\`) against \`cargo test -p mechgen\`, the runtime's unit tests and"
        echo "doctests, a few seconds a mutant; a mutant of the shipped mechanisms' analyses"
        echo "(\`mechanisms/\`) against \`cargo test -p mechanisms\`, the library's unit tests and"
        echo "doctests and the command-line program's end-to-end tests, some 15 seconds a mutant."
        echo "*Caught*: a test failed. *Missed*: every test passed (a survivor). *Unviable*: the"
        echo "mutant does not compile. *Timeout*: the tests ran past the limit (a mutant that hangs"
        echo "a solver). A file's counts may add up \`--iterate\` runs, which test again only the"
        echo "mutants not yet caught: the counts are of the tests at its commit. A file run in"
        echo "part (\`--from\`, the rest of a run cut short) counts only the mutants run, whose"
        echo "positions in cargo-mutants' order are listed under the table. A file changed since"
        echo "its commit is marked so: its row is of the file as it was then, and"
        echo "\`bash tests/mutants.sh FILE\` brings it up to date."
        echo
        echo "| file | commit | mutants | caught | missed | unviable | timeout |"
        echo "|---|---|---:|---:|---:|---:|---:|"
        for file in "${run_files[@]}"; do
            IFS=$'\t' read -r commit total caught missed unviable timeout part < <(recorded "$file")
            changed=""
            if ! git diff --quiet "${commit%-dirty}" HEAD -- "$file" 2>/dev/null ||
                ! git diff --quiet HEAD -- "$file"; then
                changed=" (file changed since)"
                changed_since+=("$file")
            fi
            if [ -n "$part" ]; then
                partial+=("\`$file\`: mutants $part.")
                total="$total of ${part##* of }"
            fi
            echo "| \`$file\` | \`$commit\`$changed | $total | $caught | $missed | $unviable | $timeout |"
        done
        echo
        if [ "${#partial[@]}" -gt 0 ]; then
            echo "Run in part (the other mutants of these files were not run):"
            printf -- '- %s\n' "${partial[@]}"
            echo
        fi
        if [ "${#no_mutants[@]}" -gt 0 ]; then
            echo "No mutants to make (declarations and re-exports): $(printf '`%s` ' "${no_mutants[@]}" | sed 's/ $//')."
            echo
        fi
        echo "Never run:"
        if [ "${#not_run[@]}" -gt 0 ]; then
            echo "$(printf '`%s` ' "${not_run[@]}")(the rest of the runtime);"
        fi
        if [ "${#not_run_analyses[@]}" -gt 0 ]; then
            echo "$(printf '`%s` ' "${not_run_analyses[@]}")(the rest of the shipped analyses);"
        fi
        if [ "$((${#not_run[@]} + ${#not_run_analyses[@]}))" -gt 0 ]; then
            echo "nor the macro (\`mechgen-macros/\`), nor the shipped mechanisms' declarations and"
        else
            echo "the macro (\`mechgen-macros/\`), and the shipped mechanisms' declarations and"
        fi
        echo "command-line program (the other files of \`mechanisms/\`)."
        echo
        echo "## Survivors"
        echo
        # Grouped by explanation, each written once, the unexplained first.
        local -A members=()
        local reasons=()
        for line in "${survivors[@]}"; do
            [ -n "$line" ] || continue
            why=$(explanation "$line")
            case $why in
                Equivalent*) equivalent=$((equivalent + 1)) ;;
                "") why="**Unexplained.**"; unexplained=$((unexplained + 1)) ;;
                *) not_killed=$((not_killed + 1)) ;;
            esac
            [ -n "${members[$why]:-}" ] || reasons+=("$why")
            members[$why]+="- \`$line\`"$'\n'
        done
        for why in "${reasons[@]}"; do
            [ "$why" = "**Unexplained.**" ] || continue
            printf '%s\n%s\n' "$why" "${members[$why]}"
        done
        for why in "${reasons[@]}"; do
            [ "$why" != "**Unexplained.**" ] || continue
            printf '%s\n%s\n' "${members[$why]}" "$why"
            echo
        done
        echo
        echo "${#survivors[@]} survivors: $equivalent equivalent, $not_killed not killed (with the"
        echo "reason), $unexplained unexplained."
        if [ "${#changed_since[@]}" -gt 0 ]; then
            echo
            echo "Changed since their run (their rows and survivors are of the file at its commit):"
            echo "$(printf '`%s` ' "${changed_since[@]}" | sed 's/ $//')."
        fi
        # Explanations of mutants that no longer survive: a test kills them now, or the code
        # moved; either way the explanation should go.
        # (Sets, not `printf | grep -q`: grep leaving early can fail printf with SIGPIPE,
        # which pipefail makes a failed test.)
        local stale=()
        local -A is_run=() is_survivor=()
        for file in "${run_files[@]}"; do is_run[$file]=1; done
        for line in "${survivors[@]}"; do is_survivor[$line]=1; done
        while IFS= read -r line; do
            # Only for the files run: the others' survivors are not known.
            file=${line%%:*}
            [ -n "${is_run[$file]:-}" ] || continue
            if [ -n "${is_survivor[$line]:-}" ]; then
                continue
            elif [ -n "$(recorded "$file" | cut -f7)" ]; then
                # Run in part: the mutant may be among those not run.
                not_tested+=("$line")
            else
                stale+=("$line")
            fi
        done < <(grep -E '^[^# ]' "$EXPLAINED")
        if [ "${#stale[@]}" -gt 0 ]; then
            echo
            echo "Stale explanations in \`$EXPLAINED\` (no such survivor):"
            printf -- '- `%s`\n' "${stale[@]}"
        fi
        if [ "${#not_tested[@]}" -gt 0 ]; then
            echo
            echo "Explanations in \`$EXPLAINED\` of mutants of files run in part that are not"
            echo "survivors, maybe not run, neither confirmed nor stale:"
            printf -- '- `%s`\n' "${not_tested[@]}"
        fi
    } > "$REPORT"
    echo "wrote $REPORT ($unexplained unexplained survivors)"
}

ITERATE=0
FROM=1
while :; do
    case "${1:-}" in
        --iterate) ITERATE=1; shift ;;
        --from)
            FROM=${2:?--from takes the position of the first mutant to run}
            shift 2
            [ "$#" -gt 0 ] || { echo "--from takes the files to run" >&2; exit 1; }
            ;;
        *) break ;;
    esac
done
case "${1:-}" in
    --report) report ;;
    "") install; run "${FILES[@]}"; report ;;
    *) install; run "$@"; report ;;
esac
