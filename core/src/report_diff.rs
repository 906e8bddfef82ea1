//! Two reports compared number by number (`flexmodes diff`): every number that moved beyond a
//! relative tolerance, every entry added or removed, and every other value that changed, key
//! by key; wall times are left out.
//!
//! A number $a$ moved to $b$ when
//! $$ |a - b| > \mathrm{rtol}\,\max(|a|, |b|), $$
//! so a change from 0 to anything is a move; JSON's `null` (a NaN or an infinity, which JSON
//! cannot hold) equals only `null`.

use serde_json::Value;

/// Result keys that hold wall times, or numbers computed from them (a growth exponent of the
/// times): they differ from run to run and are not compared. A key is left out, with all it
/// holds, when its name is one of these.
pub const TIMING_KEYS: [&str; 10] = [
    "wall_time_s",
    "offline_s",
    "online_s",
    "full_modes_s",
    "amls_s",
    "lanczos_s",
    "cb_s",
    "mc_s",
    "cb_exponent",
    "mc_exponent",
];

/// How two reports are compared.
#[derive(Debug, Clone, PartialEq)]
pub struct DiffParameters {
    /// Relative tolerance: numbers within it are equal.
    pub rtol: f64,
    /// Numbers whose magnitudes are both below this are equal (rounding noise: residuals,
    /// defects); 0 compares every number.
    pub floor: f64,
    /// Key names left out with everything below them (default: [`TIMING_KEYS`]).
    pub ignore: Vec<String>,
}

impl Default for DiffParameters {
    fn default() -> Self {
        Self {
            rtol: 1e-12,
            floor: 0.0,
            ignore: TIMING_KEYS.iter().map(|k| k.to_string()).collect(),
        }
    }
}

/// One difference between two reports, at a dotted key (`results.reduced_hz.cb[2]`).
#[derive(Debug, Clone, PartialEq)]
pub enum Change {
    /// A number moved beyond the tolerance.
    Moved {
        key: String,
        old: f64,
        new: f64,
        /// $|a - b| / \max(|a|, |b|)$.
        relative: f64,
    },
    /// A value of another kind changed (text, a flag, a number turned `null`).
    Differs { key: String, old: Value, new: Value },
    /// An entry only the new report has.
    Added { key: String, new: Value },
    /// An entry only the old report has.
    Removed { key: String, old: Value },
}

impl std::fmt::Display for Change {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Change::Moved {
                key,
                old,
                new,
                relative,
            } => write!(
                f,
                "{key}: {} → {} (relative {relative:.1e})",
                Value::from(*old),
                Value::from(*new)
            ),
            Change::Differs { key, old, new } => write!(f, "{key}: {old} → {new}"),
            Change::Added { key, new } => write!(f, "{key}: added ({})", short(new)),
            Change::Removed { key, old } => write!(f, "{key}: removed (was {})", short(old)),
        }
    }
}

/// A value's text, cut to 80 characters.
fn short(v: &Value) -> String {
    let text = v.to_string();
    match text.char_indices().nth(80) {
        Some((i, _)) => format!("{}…", &text[..i]),
        None => text,
    }
}

/// Every difference between `old` and `new` under `parameters`, in key order, and the count
/// of numbers compared.
pub fn diff_reports(old: &Value, new: &Value, parameters: &DiffParameters) -> (Vec<Change>, usize) {
    let mut walk = Walk {
        parameters,
        changes: Vec::new(),
        compared: 0,
    };
    walk.value("", old, new);
    (walk.changes, walk.compared)
}

struct Walk<'a> {
    parameters: &'a DiffParameters,
    changes: Vec<Change>,
    compared: usize,
}

impl Walk<'_> {
    /// An entry of an object or an array on either side.
    fn entry(&mut self, key: String, old: Option<&Value>, new: Option<&Value>) {
        match (old, new) {
            (Some(x), Some(y)) => self.value(&key, x, y),
            (Some(x), None) => self.changes.push(Change::Removed {
                key,
                old: x.clone(),
            }),
            (None, Some(y)) => self.changes.push(Change::Added {
                key,
                new: y.clone(),
            }),
            (None, None) => {}
        }
    }

    fn value(&mut self, key: &str, old: &Value, new: &Value) {
        match (old, new) {
            (Value::Object(a), Value::Object(b)) => {
                let mut names: Vec<&String> = a.keys().chain(b.keys()).collect();
                names.sort();
                names.dedup();
                for name in names {
                    if self.parameters.ignore.iter().any(|i| i == name) {
                        continue;
                    }
                    let at = if key.is_empty() {
                        name.clone()
                    } else {
                        format!("{key}.{name}")
                    };
                    self.entry(at, a.get(name), b.get(name));
                }
            }
            (Value::Array(a), Value::Array(b)) => {
                for i in 0..a.len().max(b.len()) {
                    let at = format!("{key}[{i}]");
                    self.entry(at, a.get(i), b.get(i));
                }
            }
            (Value::Number(a), Value::Number(b)) => {
                self.compared += 1;
                let (Some(a), Some(b)) = (a.as_f64(), b.as_f64()) else {
                    return;
                };
                let relative = relative_change(a, b);
                let noise = a.abs().max(b.abs()) < self.parameters.floor;
                if relative > self.parameters.rtol && !noise {
                    self.changes.push(Change::Moved {
                        key: key.to_string(),
                        old: a,
                        new: b,
                        relative,
                    });
                }
            }
            (a, b) if a == b => {}
            (a, b) => self.changes.push(Change::Differs {
                key: key.to_string(),
                old: a.clone(),
                new: b.clone(),
            }),
        }
    }
}

/// `value` without the keys `parameters` leaves out (a baseline holds what is compared).
pub fn without_ignored(value: &Value, parameters: &DiffParameters) -> Value {
    match value {
        Value::Object(m) => Value::Object(
            m.iter()
                .filter(|(k, _)| !parameters.ignore.iter().any(|i| i == *k))
                .map(|(k, v)| (k.clone(), without_ignored(v, parameters)))
                .collect(),
        ),
        Value::Array(a) => Value::Array(a.iter().map(|v| without_ignored(v, parameters)).collect()),
        v => v.clone(),
    }
}

/// $|a - b| / \max(|a|, |b|)$, 0 for equal numbers (zeros included).
pub fn relative_change(a: f64, b: f64) -> f64 {
    if a == b {
        0.0
    } else {
        (a - b).abs() / a.abs().max(b.abs())
    }
}

#[cfg(test)]
mod report_diff_tests {
    use super::*;
    use serde_json::json;

    fn report(hz: f64, wall: f64) -> Value {
        json!({
            "scene": "s",
            "parameters": {"modes": 6},
            "results": {"hz": [1.0, hz], "wall_time_s": {"cb": wall}, "text": "ok"},
        })
    }

    #[test]
    fn a_twelfth_digit_moves_and_a_wall_time_does_not() {
        let p = DiffParameters::default();
        let (same, compared) = diff_reports(&report(2.0, 0.1), &report(2.0, 0.7), &p);
        assert!(same.is_empty(), "{same:?}");
        assert_eq!(compared, 3);
        let (changes, _) = diff_reports(&report(2.0, 0.1), &report(2.0 * (1.0 + 3e-12), 0.1), &p);
        assert_eq!(changes.len(), 1, "{changes:?}");
        let Change::Moved { key, relative, .. } = &changes[0] else {
            panic!("{changes:?}");
        };
        assert_eq!(key, "results.hz[1]");
        assert!((relative - 3e-12).abs() < 1e-13);
        // Within the tolerance: equal.
        let (within, _) = diff_reports(&report(2.0, 0.1), &report(2.0 * (1.0 + 5e-13), 0.1), &p);
        assert!(within.is_empty(), "{within:?}");
        // Below a floor, rounding noise is equal; above it, the same move is caught.
        let floor = DiffParameters {
            floor: 1e-9,
            ..Default::default()
        };
        let tiny = |x: f64| json!({"residual": x});
        assert!(
            diff_reports(&tiny(3e-15), &tiny(7e-15), &floor)
                .0
                .is_empty()
        );
        assert_eq!(diff_reports(&tiny(3e-15), &tiny(7e-15), &p).0.len(), 1);
        assert_eq!(diff_reports(&tiny(3e-9), &tiny(7e-9), &floor).0.len(), 1);
    }

    #[test]
    fn added_removed_and_other_values_are_named() {
        let p = DiffParameters::default();
        let old = json!({"a": [1, 2, 3], "b": "x", "c": null, "d": 0.0});
        let new = json!({"a": [1, 2], "b": "y", "c": 1.0, "e": true, "d": 1e-300});
        let (changes, _) = diff_reports(&old, &new, &p);
        let text: Vec<String> = changes.iter().map(|c| c.to_string()).collect();
        assert_eq!(
            text,
            [
                "a[2]: removed (was 3)",
                "b: \"x\" → \"y\"",
                "c: null → 1.0",
                "d: 0.0 → 1e-300 (relative 1.0e0)",
                "e: added (true)",
            ],
        );
    }
}
