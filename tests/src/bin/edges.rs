//! The large run of the edge checks (issue 12): a million seeded random cases over every
//! shipped mechanism, float type and entry point, at link ratios up to 1e8 and scales across
//! each float's range, inputs anywhere and placed at, just inside and just outside the limit
//! angles, each judged against the multiple-precision oracle by the accuracy contract
//! (`mechgen_tests::oracle::judge`). Prints the cases per mechanism and float, every failure
//! class with its count and one reproducer, and exits nonzero if any case failed.
//!
//! `cargo run --release -p mechgen-tests --bin edges -- [cases] [seed] [family]`
//! (defaults: 1000000 cases, seed 12, `everything`; the families are
//! `mechgen_tests::oracle::draw::FAMILIES`).

use std::collections::BTreeMap;
use std::time::Instant;

use mechgen_tests::oracle::draw::{self, Family, Rng};
use mechgen_tests::oracle::judge;

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args
        .next()
        .map_or(1_000_000, |a| a.parse().expect("a case count"));
    let seed: u64 = args.next().map_or(12, |a| a.parse().expect("a seed"));
    let name = args.next().unwrap_or_else(|| "everything".to_string());
    let family: Family =
        draw::family(&name).unwrap_or_else(|| panic!("no family {name}: {:?}", draw::FAMILIES));
    let start = Instant::now();
    // (mechanism, float) → (cases, outcomes)
    let mut counts: BTreeMap<(String, String), (u64, BTreeMap<String, u64>)> = BTreeMap::new();
    // class → (count, first reproducer, its detail, case number)
    let mut failures: BTreeMap<String, (u64, String, String, u64)> = BTreeMap::new();
    let mut failed_cases = 0u64;
    for index in 0..cases {
        let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ index);
        let case = draw::case(&family, &mut rng);
        let verdict = judge::judge(&case);
        let entry = counts
            .entry((case.kind.name().to_string(), case.float.name().to_string()))
            .or_default();
        entry.0 += 1;
        *entry.1.entry(verdict.outcome.clone()).or_default() += 1;
        if !verdict.findings.is_empty() {
            failed_cases += 1;
        }
        for finding in verdict.findings {
            let class = format!(
                "{} {}: {}",
                case.kind.name(),
                case.float.name(),
                finding.class
            );
            let slot = failures
                .entry(class)
                .or_insert_with(|| (0, case.reproducer(), finding.detail.clone(), index));
            slot.0 += 1;
        }
        if (index + 1) % 100_000 == 0 {
            eprintln!(
                "{} cases, {failed_cases} failed, {:.0} s",
                index + 1,
                start.elapsed().as_secs_f64()
            );
        }
    }
    let elapsed = start.elapsed().as_secs_f64();
    println!("# Edge run: {cases} cases of `{name}`, seed {seed}, {elapsed:.0} s\n");
    println!("| mechanism | float | cases | outcomes |\n|---|---|---|---|");
    for ((kind, float), (n, outcomes)) in &counts {
        let outcomes: Vec<String> = outcomes.iter().map(|(o, c)| format!("{o} {c}")).collect();
        println!("| {kind} | {float} | {n} | {} |", outcomes.join(", "));
    }
    println!(
        "\n{failed_cases} of {cases} cases broke the contract, in {} classes:\n",
        failures.len()
    );
    for (class, (count, reproducer, detail, index)) in &failures {
        println!("- **{class}**: {count} cases; e.g. case {index}: `{reproducer}`: {detail}");
    }
    if failed_cases > 0 {
        std::process::exit(1);
    }
}
