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

/// What one worker saw.
#[derive(Default)]
struct Tally {
    /// (mechanism, float) → (cases, outcomes)
    counts: BTreeMap<(String, String), (u64, BTreeMap<String, u64>)>,
    /// class → (count, first reproducer, its detail, case number)
    failures: BTreeMap<String, (u64, String, String, u64)>,
    failed_cases: u64,
}

/// Draws and judges case `index` of the run.
fn run_one(family: &Family, seed: u64, index: u64, tally: &mut Tally) {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ index);
    let case = draw::case(family, &mut rng);
    let verdict = judge::judge(&case);
    let entry = tally
        .counts
        .entry((case.kind.name().to_string(), case.float.name().to_string()))
        .or_default();
    entry.0 += 1;
    *entry.1.entry(verdict.outcome.clone()).or_default() += 1;
    if !verdict.findings.is_empty() {
        tally.failed_cases += 1;
    }
    for finding in verdict.findings {
        let class = format!(
            "{} {}: {}",
            case.kind.name(),
            case.float.name(),
            finding.class
        );
        let slot = tally
            .failures
            .entry(class)
            .or_insert_with(|| (0, case.reproducer(), finding.detail.clone(), index));
        slot.0 += 1;
    }
}

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args
        .next()
        .map_or(1_000_000, |a| a.parse().expect("a case count"));
    let seed: u64 = args.next().map_or(12, |a| a.parse().expect("a seed"));
    let name = args.next().unwrap_or_else(|| "everything".to_string());
    let family: Family =
        draw::family(&name).unwrap_or_else(|| panic!("no family {name}: {:?}", draw::FAMILIES));
    if let Ok(index) = std::env::var("EDGES_ONLY") {
        // One case, in full: `EDGES_ONLY=<case> edges <cases> <seed> <family>`.
        let index: u64 = index.parse().expect("a case number");
        let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ index);
        let case = draw::case(&family, &mut rng);
        println!(
            "{case:#?}\n{}\n{:#?}",
            case.reproducer(),
            judge::judge(&case)
        );
        return;
    }
    let start = Instant::now();
    // Two workers (the machine has two cores), taking every other case; results merged in
    // case order, so the report does not depend on the threads' timing.
    let workers = std::thread::available_parallelism()
        .map_or(1, |n| n.get())
        .min(2) as u64;
    let results: Vec<Tally> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|worker| {
                let family = &family;
                scope.spawn(move || {
                    let mut tally = Tally::default();
                    let mut index = worker;
                    while index < cases {
                        run_one(family, seed, index, &mut tally);
                        index += workers;
                        if worker == 0 && index % 100_000 < workers {
                            eprintln!("{index} cases, {:.0} s", start.elapsed().as_secs_f64());
                        }
                    }
                    tally
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a worker"))
            .collect()
    });
    let mut counts: BTreeMap<(String, String), (u64, BTreeMap<String, u64>)> = BTreeMap::new();
    let mut failures: BTreeMap<String, (u64, String, String, u64)> = BTreeMap::new();
    let mut failed_cases = 0u64;
    for tally in results {
        failed_cases += tally.failed_cases;
        for (key, (n, outcomes)) in tally.counts {
            let entry = counts.entry(key).or_default();
            entry.0 += n;
            for (o, c) in outcomes {
                *entry.1.entry(o).or_default() += c;
            }
        }
        for (class, (count, reproducer, detail, index)) in tally.failures {
            let slot = failures
                .entry(class)
                .or_insert_with(|| (0, reproducer.clone(), detail.clone(), index));
            slot.0 += count;
            // One reproducer per class: the first case, whichever worker met it.
            if index < slot.3 {
                (slot.1, slot.2, slot.3) = (reproducer, detail, index);
            }
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
