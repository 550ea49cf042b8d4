//! What the reports' programs stamp their figures with: the commit they were made at and the
//! machine they ran on.

use std::process::Command;

/// The short hash of HEAD, with `-dirty` if a tracked file other than Markdown differs from
/// it. The Markdown files are the reports themselves and the prose around them, which no
/// figure depends on: a report written over its last version, or beside a README being
/// edited, is still of the code at HEAD.
pub fn commit() -> String {
    let Some(hash) = output("git", &["rev-parse", "--short", "HEAD"]) else {
        return "unknown".into();
    };
    let status = [
        "status",
        "--porcelain",
        "--untracked-files=no",
        "--",
        ":/",
        ":(top,exclude,glob)**/*.md",
    ];
    match output("git", &status) {
        Some(s) if s.is_empty() => hash,
        _ => format!("{hash}-dirty"),
    }
}

/// `program args`'s first line of output, trimmed (a tool's version), or "unknown".
pub fn tool_version(program: &str, args: &[&str]) -> String {
    output(program, args).unwrap_or_else(|| "unknown".into())
}

/// The processor, its cores, and the versions of `tools` (`(program, args)`), as
/// "AMD EPYC, 2 cores; rustc 1.95.0 (…); valgrind-3.19.0".
pub fn machine(tools: &[(&str, &[&str])]) -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let versions: Vec<String> = tools
        .iter()
        .map(|(program, args)| tool_version(program, args))
        .collect();
    format!("{cpu}, {cores} cores; {}", versions.join("; "))
}

/// A command's standard output, trimmed, if it ran and succeeded.
fn output(program: &str, args: &[&str]) -> Option<String> {
    Command::new(program)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
}
