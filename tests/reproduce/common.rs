//! Shared helpers: test data files, a seeded generator.

use std::path::PathBuf;

/// Rows of numbers from `tests/data/<name>`, skipping `#` comments.
pub fn data_rows(name: &str) -> Vec<Vec<f64>> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(name);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    rows_of(&text, name)
}

/// Rows of numbers of the embedded asset `assets/<path>` (the thesis' printed tables the
/// built-in bodies must match), skipping `#` comments.
pub fn asset_rows(path: &str) -> Vec<Vec<f64>> {
    let text = flexmodes::assets::text(path).unwrap_or_else(|| panic!("asset {path} missing"));
    rows_of(text, path)
}

fn rows_of(text: &str, name: &str) -> Vec<Vec<f64>> {
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            l.split_whitespace()
                .map(|t| {
                    t.parse::<f64>()
                        .unwrap_or_else(|e| panic!("{name}: {t}: {e}"))
                })
                .collect()
        })
        .collect()
}

/// A printed number and the tolerance "to all printed digits" (half a unit in its last
/// printed significant digit; zeros must come out below `1e-9`).
#[derive(Debug, Clone, Copy)]
pub struct Printed {
    pub value: f64,
    pub tol: f64,
}

/// A published quantity from `tests/data/published.txt`, with per-value tolerances.
pub fn published(key: &str) -> Vec<Printed> {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/published.txt");
    let text = std::fs::read_to_string(path).unwrap();
    let line = text
        .lines()
        .find(|l| l.split_whitespace().next() == Some(key))
        .unwrap_or_else(|| panic!("no published value {key}"));
    line.split_whitespace()
        .skip(1)
        .map(|t| {
            let value: f64 = t.parse().unwrap();
            let tol = if value == 0.0 {
                1e-9
            } else {
                half_ulp_printed(value, printed_digits(t))
            };
            Printed { value, tol }
        })
        .collect()
}

/// Asserts `computed` reproduces each printed value within its tolerance.
#[track_caller]
pub fn assert_printed(what: &str, computed: &[f64], printed: &[Printed]) {
    assert_eq!(
        computed.len(),
        printed.len(),
        "{what}: lengths {computed:?} vs {printed:?}"
    );
    for (i, (c, p)) in computed.iter().zip(printed).enumerate() {
        assert!(
            (c - p.value).abs() <= p.tol,
            "{what}[{i}]: computed {c} vs printed {} (tolerance {:e})",
            p.value,
            p.tol
        );
    }
}

/// Half a unit in the last of `digits` significant digits of `x`: the tolerance that says
/// "reproduces the printed value to all printed digits".
pub fn half_ulp_printed(x: f64, digits: i32) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    0.5 * 10f64.powi(x.abs().log10().floor() as i32 - (digits - 1))
}

/// Significant digits of a printed number such as `5.94776` or `0.0826`.
pub fn printed_digits(s: &str) -> i32 {
    let t = s.trim_start_matches('-');
    let digits: String = t.chars().filter(|c| c.is_ascii_digit()).collect();
    digits.trim_start_matches('0').len() as i32
}

/// A small deterministic generator (SplitMix64), so property tests are seeded and
/// reproducible without a dependency.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E3779B97F4A7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58476D1CE4E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D049BB133111EB);
        z ^ (z >> 31)
    }
    /// Uniform in [-1, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }
}
