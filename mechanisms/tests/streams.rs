//! The sweep streams: a closed pipe ends it quietly, and a long sweep takes constant memory.

use std::io::{BufRead, BufReader, Read};
use std::process::{Command, Stdio};

fn program() -> Command {
    Command::new(env!("CARGO_BIN_EXE_mechanisms"))
}

fn scratch(name: &str) -> std::path::PathBuf {
    let path = std::env::temp_dir().join(format!("mechanisms-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&path).ok();
    path
}

#[test]
fn a_closed_pipe_ends_the_program_quietly_with_success() {
    let out_dir = scratch("pipe");
    let mut child = program()
        .args([
            "sweep", "four-bar", "180", "80", "200", "150", "--step", "0.001",
        ])
        .args(["--csv", "-", "--out-dir", out_dir.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read the header, as `head -1` would, and close the pipe.
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("input_deg,segment,"));
    let status = child.wait().unwrap();
    let stderr = read_stderr(&mut child);
    std::fs::remove_dir_all(&out_dir).ok();
    assert_eq!(status.code(), Some(0), "{stderr}");
    assert_eq!(stderr, "");
}

/// A closed standard error (`mechanisms … 2>&1 | head -0`) is no panic: an error still
/// exits 1, a notice nobody can read is dropped.
#[test]
fn a_closed_standard_error_is_no_panic() {
    for (args, code) in [
        (&["analyse", "four-bar", "0", "1", "1", "1"][..], 1),
        (
            &[
                "tolerance",
                "four-bar",
                "180",
                "80",
                "200",
                "150",
                "--step",
                "90",
                "--svg",
            ][..],
            0,
        ),
    ] {
        let out_dir = scratch("stderr");
        std::fs::create_dir_all(&out_dir).unwrap();
        let mut args: Vec<String> = args.iter().map(|a| a.to_string()).collect();
        if args.last().is_some_and(|a| a == "--svg") {
            args.push(out_dir.join("t.svg").to_str().unwrap().to_string());
        }
        let mut child = program()
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stderr.take());
        let status = child.wait().unwrap();
        std::fs::remove_dir_all(&out_dir).ok();
        assert_eq!(status.code(), Some(code), "{args:?}");
    }
}

/// The child's peak resident memory in kB, read from `/usr/bin/time -v` where there is one,
/// else from the highest `VmHWM` its `/proc/<pid>/status` showed while it ran.
#[cfg(target_os = "linux")]
fn peak_resident_kb(args: &[&str]) -> u64 {
    let time = std::path::Path::new("/usr/bin/time");
    let mut command = if time.exists() {
        let mut command = Command::new(time);
        command.arg("-v").arg(env!("CARGO_BIN_EXE_mechanisms"));
        command
    } else {
        program()
    };
    let mut child = command
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let status_file = format!("/proc/{}/status", child.id());
    let mut stdout = child.stdout.take().unwrap();
    let mut buffer = vec![0; 1 << 16];
    let (mut bytes, mut peak) = (0, 0);
    loop {
        let read = stdout.read(&mut buffer).unwrap();
        if read == 0 {
            break;
        }
        bytes += read;
        if let Ok(status) = std::fs::read_to_string(&status_file) {
            let hwm = status
                .lines()
                .find_map(|line| line.strip_prefix("VmHWM:"))
                .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok());
            peak = peak.max(hwm.unwrap_or(0));
        }
    }
    let stderr = read_stderr(&mut child);
    assert!(child.wait().unwrap().success(), "{stderr}");
    assert!(bytes > 100_000_000, "the table was written: {bytes} bytes");
    assert!(stderr.contains("1000000 samples"), "{stderr}");
    if time.exists() {
        stderr
            .lines()
            .find_map(|line| {
                line.trim()
                    .strip_prefix("Maximum resident set size (kbytes):")
            })
            .expect("time -v reports the peak")
            .trim()
            .parse()
            .unwrap()
    } else {
        peak
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_million_sample_sweep_to_standard_output_stays_under_30_mb() {
    let out_dir = scratch("memory");
    let peak = peak_resident_kb(&[
        "sweep",
        "four-bar",
        "180",
        "80",
        "200",
        "150",
        "--step",
        "0.00036",
        "--csv",
        "-",
        "--out-dir",
        out_dir.to_str().unwrap(),
    ]);
    std::fs::remove_dir_all(&out_dir).ok();
    assert!(peak > 0 && peak < 30 * 1024, "peak resident {peak} kB");
}

/// Everything the child wrote to its standard error, once it has closed it.
fn read_stderr(child: &mut std::process::Child) -> String {
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    stderr
}
