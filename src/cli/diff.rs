//! `flexmodes diff OLD NEW`: two scene reports, or two folders of them, compared number by
//! number (flexmodes_core::report_diff); exit 1 when a number moved beyond the tolerance.
//! A report is `report --json`'s object in a `.json` file, or the one a recording holds
//! (`.rrd`); in a folder, `SCENE.json` and `SCENE.rrd` (the JSON first when both are there).

use std::{
    collections::BTreeMap,
    path::{Path, PathBuf},
};

use clap::Args;
use serde_json::Value;

use crate::{
    Error, Result,
    error::ReportDiffError,
    record::recorded_report,
    report_diff::{DiffParameters, diff_reports, without_ignored},
};

/// The arguments of `diff`.
#[derive(Debug, Args)]
pub(super) struct DiffArgs {
    /// The old report: a `.json` file, an `.rrd` recording, or a folder of them.
    old: PathBuf,
    /// The new report (or folder), of the same kind as the old.
    new: PathBuf,
    /// Relative tolerance: |a − b| ≤ rtol · max(|a|, |b|) is equal.
    #[arg(long, default_value_t = 1e-12)]
    rtol: f64,
    /// Numbers whose magnitudes are both below this are equal (rounding noise: residuals,
    /// defects); 0, the default, compares every number.
    #[arg(long, default_value_t = 0.0)]
    floor: f64,
    /// More key names to leave out (comma separated), besides the wall times.
    #[arg(long, value_delimiter = ',')]
    ignore: Vec<String>,
    /// Compare the wall times too (left out by default: they differ from run to run).
    #[arg(long)]
    keep_timings: bool,
    /// Write NEW's reports over OLD (a folder: `SCENE.json` each, pretty-printed, the keys
    /// left out removed) after printing the changes: a deliberate change updates its
    /// baseline this way.
    #[arg(long)]
    update: bool,
}

/// Runs `diff` with its arguments.
pub(super) fn run(arguments: DiffArgs) -> Result<()> {
    let DiffArgs {
        old,
        new,
        rtol,
        floor,
        ignore,
        keep_timings,
        update,
    } = arguments;
    check_tolerances(rtol, floor)?;
    let mut parameters = DiffParameters {
        rtol,
        floor,
        ..Default::default()
    };
    if keep_timings {
        parameters.ignore.clear();
    }
    parameters.ignore.extend(ignore);
    let pairs = report_pairs(&old, &new, update)?;
    let (mut changes, mut compared, mut reports) = (0, 0, 0);
    for (name, a, b) in &pairs {
        match (a, b) {
            (Some(a), Some(b)) => {
                let (found, count) = diff_reports(a, b, &parameters);
                reports += 1;
                compared += count;
                changes += found.len();
                for change in &found {
                    println!("{name}: {change}");
                }
            }
            (Some(_), None) => {
                changes += 1;
                println!("{name}: only in {}", old.display());
            }
            (None, Some(_)) => {
                changes += 1;
                println!("{name}: only in {}", new.display());
            }
            (None, None) => {}
        }
    }
    let left_out = if parameters.ignore.is_empty() {
        "nothing left out".to_string()
    } else {
        format!("left out: {}", parameters.ignore.join(", "))
    };
    println!(
        "{compared} numbers in {reports} report(s) compared at a relative tolerance of {rtol:e}{} \
         ({left_out}): {changes} change(s)",
        if floor > 0.0 {
            format!(" above {floor:e}")
        } else {
            String::new()
        }
    );
    if update {
        write_baseline(&old, &pairs, &parameters)?;
    }
    if changes > 0 && !update {
        return Err(ReportDiffError::Differ {
            changes,
            rtol,
            reports,
        }
        .into());
    }
    Ok(())
}

/// `--rtol` and `--floor`, each finite and not negative.
fn check_tolerances(rtol: f64, floor: f64) -> Result<()> {
    if !(rtol.is_finite() && rtol >= 0.0) {
        return Err(Error::InvalidOption {
            option: "--rtol",
            scene: None,
            reason: format!("a relative tolerance is finite and not negative, not {rtol}"),
        });
    }
    if !(floor.is_finite() && floor >= 0.0) {
        return Err(Error::InvalidOption {
            option: "--floor",
            scene: None,
            reason: format!("a floor is finite and not negative, not {floor}"),
        });
    }
    Ok(())
}

/// The reports to compare, by name: of two folders every report either holds (a side `None`
/// where one lacks it; none in common is an error unless the baseline is being updated), or
/// two files.
fn report_pairs(old: &Path, new: &Path, update: bool) -> Result<Vec<ReportPair>> {
    Ok(match (old.is_dir(), new.is_dir()) {
        (true, true) => {
            let (a, b) = (reports_in(old)?, reports_in(new)?);
            if !update && !a.keys().any(|k| b.contains_key(k)) {
                return Err(ReportDiffError::NothingInCommon {
                    old: old.display().to_string(),
                    new: new.display().to_string(),
                }
                .into());
            }
            let mut names: Vec<&String> = a.keys().chain(b.keys()).collect();
            names.sort();
            names.dedup();
            let mut pairs = Vec::new();
            for name in names {
                let load =
                    |m: &BTreeMap<String, PathBuf>| m.get(name).map(|p| report(p)).transpose();
                pairs.push((name.clone(), load(&a)?, load(&b)?));
            }
            pairs
        }
        (false, false) => vec![(
            new.display().to_string(),
            Some(report(old)?),
            Some(report(new)?),
        )],
        _ => {
            return Err(Error::InvalidOption {
                option: "OLD NEW",
                scene: None,
                reason: format!(
                    "compare two files or two folders: {} is a {} and {} a {}",
                    old.display(),
                    kind(old),
                    new.display(),
                    kind(new)
                ),
            });
        }
    })
}

/// A report's name and its old and new JSON, each `None` where that side lacks it.
type ReportPair = (String, Option<Value>, Option<Value>);

fn kind(path: &Path) -> &'static str {
    if path.is_dir() {
        "folder"
    } else if path.exists() {
        "file"
    } else {
        "path that does not exist"
    }
}

/// The reports of a folder by scene: `SCENE.json` or `SCENE.rrd`, the JSON first.
fn reports_in(folder: &Path) -> Result<BTreeMap<String, PathBuf>> {
    let entries =
        std::fs::read_dir(folder).map_err(|source| Error::io(folder.to_path_buf(), source))?;
    let mut found: BTreeMap<String, PathBuf> = BTreeMap::new();
    for entry in entries {
        let path = entry
            .map_err(|source| Error::io(folder.to_path_buf(), source))?
            .path();
        let (Some(stem), Some(ext)) = (
            path.file_stem().and_then(|s| s.to_str()),
            path.extension().and_then(|s| s.to_str()),
        ) else {
            continue;
        };
        match ext {
            "json" => {
                found.insert(stem.to_string(), path);
            }
            "rrd" => {
                found.entry(stem.to_string()).or_insert(path);
            }
            _ => {}
        }
    }
    Ok(found)
}

/// The report in a `.rrd` recording or a `.json` file.
fn report(path: &Path) -> Result<Value> {
    if path.extension().and_then(|s| s.to_str()) == Some("rrd") {
        return recorded_report(path);
    }
    let text =
        std::fs::read_to_string(path).map_err(|source| Error::io(path.to_path_buf(), source))?;
    let value: Value = serde_json::from_str(&text).map_err(|e| ReportDiffError::NotJson {
        path: path.display().to_string(),
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    })?;
    if value.get("scene").is_none() || value.get("results").is_none() {
        return Err(ReportDiffError::NoReport {
            path: path.display().to_string(),
            why: "no `scene` and `results` keys: not a `report --json` object".into(),
        }
        .into());
    }
    Ok(value)
}

/// NEW's reports written over OLD, pretty-printed and without the keys left out: one file, or `SCENE.json` per scene in
/// OLD's folder (a scene only OLD has is left as it is).
fn write_baseline(old: &Path, pairs: &[ReportPair], parameters: &DiffParameters) -> Result<()> {
    let pretty = |v: &Value| {
        let mut text =
            serde_json::to_string_pretty(&without_ignored(v, parameters)).unwrap_or_default();
        text.push('\n');
        text
    };
    if !old.is_dir() {
        if let Some((_, _, Some(new))) = pairs.first() {
            crate::atomic_file::write_bytes_atomically(old, pretty(new).as_bytes())?;
        }
        return Ok(());
    }
    for (name, _, new) in pairs {
        if let Some(new) = new {
            let path = old.join(format!("{name}.json"));
            crate::atomic_file::write_bytes_atomically(&path, pretty(new).as_bytes())?;
        }
    }
    println!("{} written from the new reports", old.display());
    Ok(())
}
