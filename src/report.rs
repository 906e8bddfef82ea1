//! Numeric results of a scene: the `report --json` object and the human table.

use serde_json::{Map, Value, json};

/// `{"scene": ID, "parameters": {...}, "results": {...}}` plus a markdown table for people.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Scene id.
    pub scene: String,
    /// The parameters the scene ran with.
    pub parameters: Map<String, Value>,
    /// Results; the documented keys (README) are stable.
    pub results: Map<String, Value>,
    /// The result table in markdown (printed by `report`, shown in the `scene` panel).
    pub table: String,
}

impl Report {
    /// An empty report for a scene.
    pub fn new(scene: &str) -> Self {
        Self {
            scene: scene.into(),
            parameters: Map::new(),
            results: Map::new(),
            table: String::new(),
        }
    }

    /// The JSON object of `report --json`.
    pub fn to_json(&self) -> Value {
        json!({
            "scene": self.scene,
            "parameters": Value::Object(self.parameters.clone()),
            "results": Value::Object(self.results.clone()),
        })
    }

    /// A result by dotted key (`reduced_hz.cb`).
    pub fn result(&self, dotted: &str) -> Option<&Value> {
        let mut parts = dotted.split('.');
        let mut v = self.results.get(parts.next()?)?;
        for p in parts {
            v = v.get(p)?;
        }
        Some(v)
    }

    /// A numeric array result by dotted key.
    pub fn result_vec(&self, dotted: &str) -> Option<Vec<f64>> {
        self.result(dotted)?
            .as_array()?
            .iter()
            .map(Value::as_f64)
            .collect()
    }
}

/// Rounds for JSON/markdown output without losing the digits the thesis prints (9 significant).
pub fn sig(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let digits = 9 - x.abs().log10().ceil() as i32;
    let f = 10f64.powi(digits.clamp(-300, 300));
    (x * f).round() / f
}

/// Rounds each entry with [`sig`].
pub fn sig_vec(v: &[f64]) -> Vec<f64> {
    v.iter().map(|&x| sig(x)).collect()
}

/// A markdown table with a header row.
pub fn markdown_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let mut s = format!(
        "| {} |\n|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    for r in rows {
        s.push_str(&format!("| {} |\n", r.join(" | ")));
    }
    s
}

/// Formats a list of frequencies with `digits` significant digits.
pub fn fmt_hz(v: &[f64]) -> String {
    v.iter().map(|f| sig6(*f)).collect::<Vec<_>>().join(", ")
}

/// Six significant digits, as the thesis prints.
pub fn sig6(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let mag = x.abs().log10().floor() as i32;
    let decimals = (5 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Five significant digits in MATLAB's `short g` manner (`2.5e+05`, `416.07`).
pub fn sig5(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let digits = 5 - x.abs().log10().ceil() as i32;
    let f = 10f64.powi(digits.clamp(-300, 300));
    (x * f).round() / f
}
