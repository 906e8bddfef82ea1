//! `flexmodes bench --body FILE --boundary SET --modes N`: Craig–Bampton export of a body as a
//! whole process against SciPy's CHOLMOD route on the same body, measured in the same run.
//!
//! Both run as separate processes, one after the other, `repeats` times; the medians of their
//! wall times give the ratio. The peer is `../shared/bench/peers_body_cb.py --cholmod` (or the
//! script `--peer` names), which also prints its Craig–Bampton frequencies: they are compared
//! with the ones flexmodes wrote, so the two did the same work. Timings are reported, never
//! asserted.

use std::{
    path::{Path, PathBuf},
    process::Command,
    time::Instant,
};

use serde_json::{Value, json};

use crate::{Error, Result, report::sig};

/// What to run.
#[derive(Debug, Clone)]
pub struct ExportBenchParameters {
    /// The body file.
    pub body: PathBuf,
    /// The interface: node-set names (the peer takes one set, or `rbe2:SET`).
    pub boundary: Vec<String>,
    /// Kept fixed-interface modes.
    pub modes: usize,
    /// Runs of each process; their median is reported.
    pub repeats: usize,
    /// The peer script (run with `python3 SCRIPT BODY SET MODES --cholmod`).
    pub peer: PathBuf,
}

/// One process's wall times, peak resident memory and what it printed.
#[derive(Debug, Clone)]
struct Runs {
    seconds: Vec<f64>,
    /// The largest peak resident set of the runs, MB (`None` where the system does not say).
    peak_mb: Option<f64>,
    stdout: String,
    stderr: String,
}

/// Runs `command` to its end, its output captured: its exit status, stdout, stderr and its
/// peak resident memory in MB (the kernel's `ru_maxrss` from `wait4`: the largest resident
/// set of the child and of the descendants it waited for).
fn run_measured(command: &mut Command) -> std::io::Result<(std::process::Output, Option<f64>)> {
    use std::io::Read;
    let mut child = command
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()?;
    // Both pipes drained side by side, so a child that fills one never blocks.
    let mut err_pipe = child.stderr.take().expect("piped above");
    let err_reader = std::thread::spawn(move || {
        let mut buf = Vec::new();
        err_pipe.read_to_end(&mut buf).map(|_| buf)
    });
    let mut stdout = Vec::new();
    child
        .stdout
        .take()
        .expect("piped above")
        .read_to_end(&mut stdout)?;
    let stderr = err_reader
        .join()
        .map_err(|_| std::io::Error::other("stderr reader panicked"))??;
    let (status, peak_mb) = wait_with_peak(child)?;
    Ok((
        std::process::Output {
            status,
            stdout,
            stderr,
        },
        peak_mb,
    ))
}

/// Waits for `child`, with its peak resident memory in MB.
#[cfg(target_os = "linux")]
fn wait_with_peak(
    child: std::process::Child,
) -> std::io::Result<(std::process::ExitStatus, Option<f64>)> {
    use std::os::unix::process::ExitStatusExt;
    let pid = child.id() as libc::pid_t;
    let mut status: libc::c_int = 0;
    // SAFETY: a zeroed rusage is a valid value for wait4 to fill; the pid is our own child,
    // not yet waited for (the Child handle is dropped without wait).
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let reaped = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    if reaped != pid {
        return Err(std::io::Error::last_os_error());
    }
    // ru_maxrss is in KiB on Linux.
    Ok((
        std::process::ExitStatus::from_raw(status),
        Some(usage.ru_maxrss as f64 / 1024.0),
    ))
}

#[cfg(not(target_os = "linux"))]
fn wait_with_peak(
    mut child: std::process::Child,
) -> std::io::Result<(std::process::ExitStatus, Option<f64>)> {
    Ok((child.wait()?, None))
}

fn run_timed(mut command: Command, repeats: usize, what: &'static str) -> Result<Runs> {
    let mut seconds = Vec::with_capacity(repeats);
    let mut peak_mb: Option<f64> = None;
    let mut stdout = String::new();
    let mut stderr = String::new();
    for _ in 0..repeats {
        let started = Instant::now();
        // A program that cannot be started is named by its path (`what` names the run).
        let (out, peak) = run_measured(&mut command)
            .map_err(|source| Error::io(command.get_program(), source))?;
        seconds.push(started.elapsed().as_secs_f64());
        peak_mb = match (peak_mb, peak) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        if !out.status.success() {
            return Err(Error::PeerFailed {
                peer: what,
                stderr: String::from_utf8_lossy(&out.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
                    .into(),
            });
        }
        stdout = String::from_utf8_lossy(&out.stdout).into_owned();
        stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    }
    seconds.sort_by(f64::total_cmp);
    Ok(Runs {
        seconds,
        peak_mb,
        stdout,
        stderr,
    })
}

/// The phases `export --timings` printed (`  NAME: S s (P %)`), in order.
fn phases(stderr: &str) -> Vec<(String, f64)> {
    stderr
        .lines()
        .filter_map(|line| {
            let (name, rest) = line.trim().rsplit_once(": ")?;
            let seconds = rest.split_once(" s")?.0.parse().ok()?;
            Some((name.to_string(), seconds))
        })
        .collect()
}

fn median(sorted: &[f64]) -> f64 {
    sorted[sorted.len() / 2]
}

/// Runs the bench and returns its JSON and its text table.
pub fn bench_export(p: &ExportBenchParameters) -> Result<(Value, String)> {
    let out_dir =
        std::env::temp_dir().join(format!("flexmodes-bench-export-{}", std::process::id()));
    let exe =
        std::env::current_exe().map_err(|source| Error::io("the flexmodes executable", source))?;
    let threads = crate::linalg::threads();
    let (ours, model) = our_export(p, &exe, &out_dir, threads)?;
    let our_hz: Vec<f64> = model["reduced_elastic_hz"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default();
    let peer = peer_runs(p);
    let ours_s = median(&ours.seconds);
    let our_phases = phases(&ours.stderr);
    let mut value = json!({
        "bench": "export",
        "body": p.body.display().to_string(),
        "boundary": p.boundary,
        "modes": p.modes,
        "repeats": p.repeats,
        "flexmodes_s": ours.seconds.iter().map(|&s| sig(s)).collect::<Vec<_>>(),
        "flexmodes_median_s": sig(ours_s),
        "flexmodes_hz": our_hz.iter().take(10).map(|&f| sig(f)).collect::<Vec<_>>(),
        "flexmodes_threads": threads,
        "flexmodes_peak_mb": ours.peak_mb.map(sig),
        "flexmodes_phases_s": our_phases
            .iter()
            .map(|(name, s)| json!({ "phase": name, "s": sig(*s) }))
            .collect::<Vec<_>>(),
    });
    let mut text = format!(
        "# export bench: Craig–Bampton of {} on {} with {} modes, {} run(s) each\n\n\
         | process | median s | runs s | peak MB |\n|---|---|---|---|\n\
         | flexmodes export | {:.2} | {} | {} |\n",
        p.body.display(),
        p.boundary.join(","),
        p.modes,
        p.repeats,
        ours_s,
        fmt_runs(&ours.seconds),
        fmt_peak(ours.peak_mb)
    );
    match peer {
        Ok(peer) => add_peer(
            (&mut value, &mut text),
            peer,
            (&our_hz, ours_s),
            model["zero_energy_threshold_hz"].as_f64().unwrap_or(0.0),
        ),
        Err(reason) => {
            value["peer"] = Value::Null;
            value["peer_skipped"] = json!(reason);
            text.push_str(&format!("\nSciPy peer not run: {reason}\n"));
        }
    }
    text.push_str(&format!(
        "\nflexmodes on {threads} thread(s), last run by phase: {}\n",
        our_phases
            .iter()
            .filter(|(name, _)| name != "total")
            .map(|(name, s)| format!("{name} {s:.2} s"))
            .collect::<Vec<_>>()
            .join(", ")
    ));
    Ok((value, text))
}

/// `flexmodes export` of the bench's body, timed over its repeats, and the model it wrote.
fn our_export(
    p: &ExportBenchParameters,
    exe: &std::path::Path,
    out_dir: &std::path::Path,
    threads: usize,
) -> Result<(Runs, Value)> {
    let mut own = Command::new(exe);
    own.args(["export", "--timings", "--threads"])
        .arg(threads.to_string())
        .args(["--method", "cb", "--body"])
        .arg(&p.body)
        .arg("--boundary")
        .arg(p.boundary.join(","))
        .arg("--modes")
        .arg(p.modes.to_string())
        .arg("--out")
        .arg(out_dir);
    let ours = run_timed(own, p.repeats, "flexmodes export")?;
    let model: Value = serde_json::from_slice(
        &std::fs::read(out_dir.join("model.json"))
            .map_err(|source| Error::io(out_dir.join("model.json"), source))?,
    )
    .map_err(|source| Error::PeerOutput {
        peer: "flexmodes export",
        file: "model.json",
        source,
    })?;
    let _ = std::fs::remove_dir_all(out_dir);
    Ok((ours, model))
}

/// The SciPy peer's runs beside ours: its times and memory, the ratios, and how far the
/// lowest elastic frequencies agree (the peer's rigid ones, below `threshold` Hz, left out).
fn add_peer(
    (value, text): (&mut Value, &mut String),
    (runs, peer_json): (Runs, Value),
    (our_hz, ours_s): (&[f64], f64),
    threshold: f64,
) {
    let peer_s = median(&runs.seconds);
    // The peer prints every eigenvalue of its reduced model; its rigid ones first.
    let peer_hz: Vec<f64> = peer_json["cb_hz"]
        .as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default();
    let rigid = crate::analysis::zero_energy_below(&peer_hz, threshold);
    let compared = our_hz
        .len()
        .min(peer_hz.len().saturating_sub(rigid))
        .min(10);
    let agreement = (0..compared)
        .map(|j| (our_hz[j] - peer_hz[rigid + j]).abs() / peer_hz[rigid + j])
        .fold(0.0f64, f64::max);
    let cb_s = peer_json["cb_seconds"].as_f64().unwrap_or(f64::NAN);
    value["peer"] = json!("scipy-cholmod");
    value["peer_s"] = json!(runs.seconds.iter().map(|&s| sig(s)).collect::<Vec<_>>());
    value["peer_median_s"] = json!(sig(peer_s));
    value["peer_cb_only_s"] = json!(sig(cb_s));
    value["peer_peak_mb"] = json!(runs.peak_mb.map(sig));
    value["ratio_to_peer_process"] = json!(sig(ours_s / peer_s));
    value["ratio_to_peer_cb_only"] = json!(sig(ours_s / cb_s));
    value["max_rel_hz_difference"] = json!(sig(agreement));
    text.push_str(&format!(
        "| SciPy + CHOLMOD (peers_body_cb.py --cholmod) | {peer_s:.2} | {} | {} |\n\n\
         flexmodes / SciPy: {:.2}× of its whole process, {:.2}× of its CB alone \
         ({cb_s:.2} s; the process also reads the body, imports SciPy and solves the \
         free-free problem). The {compared} lowest elastic frequencies agree to \
         {agreement}. Peak MB: the largest resident set of any run of the process.\n",
        fmt_runs(&runs.seconds),
        fmt_peak(runs.peak_mb),
        ours_s / peer_s,
        ours_s / cb_s,
        agreement = flexmodes_core::report::readable(agreement, 2),
    ));
}

fn fmt_peak(mb: Option<f64>) -> String {
    mb.map_or("–".into(), |mb| format!("{mb:.0}"))
}

fn fmt_runs(s: &[f64]) -> String {
    s.iter()
        .map(|x| format!("{x:.2}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The peer's runs and its last JSON line, or why it could not run.
fn peer_runs(p: &ExportBenchParameters) -> std::result::Result<(Runs, Value), String> {
    if !Path::new(&p.peer).is_file() {
        return Err(format!("no peer script at {}", p.peer.display()));
    }
    let [set] = p.boundary.as_slice() else {
        return Err("the peer takes one node set as interface".into());
    };
    let mut command = Command::new("python3");
    command
        .arg(&p.peer)
        .arg(&p.body)
        .arg(set)
        .arg(p.modes.to_string())
        .arg("--cholmod");
    let runs = run_timed(command, p.repeats, "the SciPy peer").map_err(|e| e.to_string())?;
    let line = runs.stdout.lines().last().unwrap_or("").to_string();
    let json: Value = serde_json::from_str(&line).map_err(|e| format!("peer output: {e}"))?;
    Ok((runs, json))
}

#[cfg(all(test, target_os = "linux"))]
mod tests {
    use super::*;

    /// A process whose pipeline holds an 80 MB line (`sort` keeps it whole) reports at least
    /// that, its descendants' peaks included; a trivial one a few MB. Output and exit status
    /// come through.
    #[test]
    fn a_child_s_peak_memory_is_measured_with_its_descendants() {
        let mut big = Command::new("sh");
        big.args(["-c", "head -c 80000000 /dev/zero | sort | wc -c"]);
        let (out, peak) = run_measured(&mut big).unwrap();
        assert!(out.status.success());
        // `sort` ends the line.
        assert_eq!(String::from_utf8_lossy(&out.stdout).trim(), "80000001");
        let big_peak = peak.expect("Linux reports ru_maxrss");
        assert!(big_peak >= 70.0, "{big_peak} MB for an 80 MB line");
        let (out, small_peak) = run_measured(&mut Command::new("true")).unwrap();
        assert!(out.status.success());
        let small_peak = small_peak.unwrap();
        // A child forked from this test process starts with its pages, so `true` may report
        // up to the test process' own peak (other tests run beside it), never more.
        let own_peak_mb = std::fs::read_to_string("/proc/self/status")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find_map(|l| l.strip_prefix("VmHWM:"))
                    .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
            })
            .map_or(0.0, |kb| kb / 1024.0);
        assert!(
            small_peak < 20.0_f64.max(own_peak_mb + 5.0),
            "{small_peak} MB for `true` (this process' peak: {own_peak_mb} MB)"
        );
        let (out, _) = run_measured(&mut Command::new("false")).unwrap();
        assert!(!out.status.success());
    }
}
