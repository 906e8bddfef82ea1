//! `diff`: two reports (JSON or recordings) compared number by number, wall times left out.

use crate::common::{flexmodes, temp_dir};
use flexmodes::report_diff::TIMING_KEYS;
use serde_json::Value;

/// The first number under `results` (depth first, wall times apart) multiplied by `factor`,
/// and its key.
fn nudge(v: &mut Value, factor: f64, key: &str) -> Option<String> {
    match v {
        Value::Object(m) => m
            .iter_mut()
            .filter(|(k, _)| !TIMING_KEYS.contains(&k.as_str()))
            .find_map(|(k, x)| {
                let at = if key.is_empty() {
                    k.clone()
                } else {
                    format!("{key}.{k}")
                };
                nudge(x, factor, &at)
            }),
        Value::Array(a) => a
            .iter_mut()
            .enumerate()
            .find_map(|(i, x)| nudge(x, factor, &format!("{key}[{i}]"))),
        Value::Number(n) => {
            let x = n.as_f64().filter(|x| *x != 0.0 && x.fract() != 0.0)?;
            *v = serde_json::json!(x * factor);
            Some(key.to_string())
        }
        _ => None,
    }
}

fn write(path: &std::path::Path, v: &Value) {
    std::fs::write(path, serde_json::to_string_pretty(v).unwrap()).unwrap();
}

/// A recording and `report --json` of one scene are the same report; a number moved in its
/// 12th digit is found by its key (exit 1) and passes a looser tolerance; wall times are
/// left out unless asked for; a file that is no report is named.
#[test]
fn diff_finds_a_twelfth_digit_and_leaves_wall_times_out() {
    let dir = temp_dir("diff");
    let rrd = dir.join("slab-sim1.rrd");
    let out = flexmodes(&["record", "slab-sim1", "--save", rrd.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = flexmodes(&["report", "slab-sim1", "--json"]);
    assert!(report.status.success());
    let original: Value = serde_json::from_slice(&report.stdout).unwrap();
    let json = dir.join("slab-sim1.json");
    write(&json, &original);
    let diff = |a: &std::path::Path, b: &std::path::Path, more: &[&str]| {
        let mut args = vec!["diff", a.to_str().unwrap(), b.to_str().unwrap()];
        args.extend(more);
        let out = flexmodes(&args);
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).to_string(),
            String::from_utf8_lossy(&out.stderr).to_string(),
        )
    };

    // The recording holds the report, timings apart.
    let (code, stdout, stderr) = diff(&rrd, &json, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    assert!(stdout.contains(": 0 change(s)"), "{stdout}");

    // One number in its 12th digit.
    let mut moved = original.clone();
    let key = nudge(&mut moved["results"], 1.0 + 4e-12, "results").unwrap();
    let nudged = dir.join("nudged.json");
    write(&nudged, &moved);
    let (code, stdout, stderr) = diff(&json, &nudged, &[]);
    assert_eq!(code, Some(1), "{stdout}");
    assert!(stdout.contains(&format!("{key}: ")), "{key}: {stdout}");
    assert!(stdout.contains(": 1 change(s)"), "{stdout}");
    assert!(
        stderr.contains("1 change(s) beyond a relative tolerance"),
        "{stderr}"
    );
    let (code, stdout, _) = diff(&json, &nudged, &["--rtol", "1e-10"]);
    assert_eq!(code, Some(0), "{stdout}");

    // Wall times differ from run to run: left out unless kept.
    let mut slower = original.clone();
    let walls = slower["results"]["wall_time_s"].as_object_mut().unwrap();
    assert!(!walls.is_empty());
    for v in walls.values_mut() {
        *v = serde_json::json!(v.as_f64().unwrap() * 3.0);
    }
    let timed = dir.join("timed.json");
    write(&timed, &slower);
    assert_eq!(diff(&json, &timed, &[]).0, Some(0));
    let (code, stdout, _) = diff(&json, &timed, &["--keep-timings"]);
    assert_eq!(code, Some(1));
    assert!(stdout.contains("results.wall_time_s."), "{stdout}");

    // Not a report: named, exit 1.
    let bad = dir.join("bad.json");
    std::fs::write(&bad, "{\"scene\": \n 3,").unwrap();
    let (code, _, stderr) = diff(&json, &bad, &[]);
    assert_eq!(code, Some(1));
    assert!(stderr.contains("bad.json: not JSON at line 2"), "{stderr}");
    let (code, _, stderr) = diff(&json, &dir, &[]);
    assert_eq!(code, Some(1));
    assert!(
        stderr.contains("compare two files or two folders"),
        "{stderr}"
    );
}
