//! The data files of `assets/`, embedded in the binary so `flexmodes` stays one file: the
//! thesis bodies' parameters and printed tables, and the example bodies in the body-file
//! format (`builtin:NAME`).

macro_rules! embed {
    ($path:literal) => {
        (
            $path,
            include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/../assets/", $path)).as_slice(),
        )
    };
}

/// Every embedded file by its path under `assets/`.
pub static FILES: &[(&str, &[u8])] = &[
    embed!("thesis/beam-app-a.toml"),
    embed!("thesis/beam-stiffness-app-a.txt"),
    embed!("thesis/slab-app-b.toml"),
    embed!("thesis/slab-table-b1.txt"),
    embed!("thesis/slab-bricks-app-b.txt"),
    embed!("thesis/plank-5-3-3.toml"),
    embed!("papers/kane-1987-beam.toml"),
    embed!("papers/rotating-cantilever-flapwise.csv"),
    embed!("papers/kane-spin-up-4.csv"),
    embed!("papers/kane-spin-up-10.csv"),
    embed!("bodies/app-b-slab/body.toml"),
    embed!("bodies/app-b-slab/k.mtx"),
    embed!("bodies/app-b-slab/m.mtx"),
    embed!("bodies/app-b-slab/nodes.csv"),
    embed!("bodies/app-b-slab/edges.csv"),
    embed!("bodies/l-bracket/body.toml"),
    embed!("bodies/l-bracket/k.mtx.gz"),
    embed!("bodies/l-bracket/m.mtx.gz"),
    embed!("bodies/l-bracket/nodes.csv"),
    embed!("bodies/l-bracket/edges.csv"),
    embed!("bodies/spun-lever/body.toml"),
    embed!("bodies/spun-lever/job.sti.gz"),
    embed!("bodies/spun-lever/job.mas.gz"),
    embed!("bodies/spun-lever/job.dof.gz"),
    embed!("bodies/spun-lever/spun.sti.gz"),
    embed!("bodies/spun-lever/spun.dof.gz"),
    embed!("bodies/spun-lever/spun.inp"),
    embed!("bodies/spun-lever/nodes.csv"),
];

/// The embedded file at `path` (relative to `assets/`).
pub fn get(path: &str) -> Option<&'static [u8]> {
    FILES.iter().find(|(p, _)| *p == path).map(|(_, b)| *b)
}

/// The embedded file at `path` as text (every text asset is UTF-8).
pub fn text(path: &str) -> Option<&'static str> {
    get(path).and_then(|b| std::str::from_utf8(b).ok())
}

/// Names of the embedded example bodies (`builtin:NAME`).
pub fn builtin_bodies() -> Vec<&'static str> {
    let mut names: Vec<&str> = FILES
        .iter()
        .filter_map(|(p, _)| p.strip_prefix("bodies/")?.strip_suffix("/body.toml"))
        .collect();
    names.dedup();
    names
}

/// Parses an embedded TOML parameter file. The assets are part of the build and every one is
/// loaded by the tests, so a failure here is a defect of the build, not of user input.
pub fn parameters<T: serde::de::DeserializeOwned>(path: &str) -> T {
    let text = text(path).unwrap_or_else(|| panic!("asset {path} is not embedded"));
    toml::from_str(text).unwrap_or_else(|e| panic!("asset {path} does not parse: {e}"))
}
