//! No file can kill the process: every reader of body files (Matrix Market, Harwell–Boeing,
//! Abaqus, NASTRAN DMIG, binary and ASCII OP4, CalculiX `.sti/.mas/.dof`, DOF maps, node
//! tables, body.toml; and `.npy`, on a written array) fed deterministic mutations of the
//! committed bodies' files, in process:
//! each must load or give a named error, never panic, abort, run away or allocate beyond
//! [`CASE_MEMORY`]. An error that names a line of the mutated file names a line it has.
//!
//! `cargo test` runs [`QUICK_CASES`]; CI runs the thorough set, ≥ 3 000 fixed seeds:
//!
//! ```sh
//! cargo test --test fuzz_readers -- --ignored --nocapture
//! ```
//!
//! A case that ever failed is kept under `tests/fuzz/regressions/` (listed in its
//! `regressions.toml`) and
//! replayed by [`every_regression_file_gives_a_named_error`].

use std::{
    alloc::{GlobalAlloc, Layout, System},
    io::{Read, Write},
    path::{Path, PathBuf},
    sync::atomic::{AtomicBool, AtomicUsize, Ordering},
    time::{Duration, Instant},
};

use flexmodes::body_file::ImportedBody;

#[path = "fuzz/mutation.rs"]
mod mutation;

#[path = "common/scratch.rs"]
#[allow(dead_code)]
mod scratch;

use mutation::{Rng, mutate};
use scratch::Scratch;

/// Bytes a case may hold at once beyond what was held when it started (1 GiB); a single
/// request above it is refused (the process aborts, naming the case: the test fails loudly).
const CASE_MEMORY: usize = 1 << 30;
/// Wall time one case may take (a debug build reading the largest committed body, with the
/// checks of its mass, takes about a second).
const CASE_TIME: Duration = Duration::from_secs(60);
/// Cases `cargo test` runs.
const QUICK_CASES: u64 = 100;
/// Cases CI runs (`--ignored`).
const THOROUGH_CASES: u64 = 3_000;

/// The system allocator, counting: bytes held, the peak since a case began, and a refusal of
/// any single request above [`CASE_MEMORY`] while a case runs.
struct Counting;

static HELD: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static IN_CASE: AtomicBool = AtomicBool::new(false);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if IN_CASE.load(Ordering::Relaxed) && layout.size() > CASE_MEMORY {
            refused(layout.size());
            return std::ptr::null_mut();
        }
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let held = HELD.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(held, Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        HELD.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if IN_CASE.load(Ordering::Relaxed) && new_size > CASE_MEMORY {
            refused(new_size);
            return std::ptr::null_mut();
        }
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            HELD.fetch_sub(layout.size(), Ordering::Relaxed);
            let held = HELD.fetch_add(new_size, Ordering::Relaxed) + new_size;
            PEAK.fetch_max(held, Ordering::Relaxed);
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// Says which request was refused before the abort that follows (stderr is unbuffered: no
/// allocation here).
fn refused(size: usize) {
    let mut digits = [0u8; 20];
    let mut n = size;
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    let mut err = std::io::stderr();
    let _ = err.write_all(b"\nfuzz_readers: a reader asked for ");
    let _ = err.write_all(&digits[i..]);
    let _ = err.write_all(b" bytes in one allocation (the case is printed above)\n");
}

/// A body file (spec) and the files it names, in the folder they share.
struct Target {
    dir: PathBuf,
    spec: String,
    files: Vec<String>,
}

/// Every committed body spec and the files it names.
fn targets() -> Vec<Target> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut dirs = Vec::new();
    for parent in ["tests/bodies", "tests/corpus", "assets/bodies"] {
        for entry in std::fs::read_dir(root.join(parent)).unwrap() {
            let dir = entry.unwrap().path();
            if dir.is_dir() {
                if dir.join("converted").is_dir() {
                    dirs.push(dir.join("converted"));
                }
                dirs.push(dir);
            }
        }
    }
    dirs.sort();
    let mut out = Vec::new();
    for dir in dirs {
        let mut specs: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".toml"))
            .collect();
        specs.sort();
        for spec in specs {
            let text = std::fs::read_to_string(dir.join(&spec)).unwrap();
            // The quoted names of files beside the spec.
            let mut files: Vec<String> = text
                .split('"')
                .skip(1)
                .step_by(2)
                .filter(|name| !name.is_empty() && dir.join(name).is_file())
                .map(str::to_string)
                .collect();
            files.sort();
            files.dedup();
            files.insert(0, spec.clone());
            out.push(Target {
                dir: dir.clone(),
                spec,
                files,
            });
        }
    }
    out
}

/// A file's bytes, decompressed when gzip (readers take plain files under the same name).
fn plain(path: &Path) -> Vec<u8> {
    let bytes = std::fs::read(path).unwrap();
    if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut out = Vec::new();
        flate2::read::GzDecoder::new(&bytes[..])
            .read_to_end(&mut out)
            .unwrap();
        out
    } else {
        bytes
    }
}

/// What one case did.
enum Outcome {
    Loaded,
    Named(String),
}

/// Loads `spec` in `dir` with the allocator's bound and the clock on; a panic, a time or
/// memory overrun, or an error that names a line the mutated file does not have is `Err`.
fn load_case(dir: &Path, spec: &str, mutated: &str, lines: usize) -> Result<Outcome, String> {
    let held = HELD.load(Ordering::Relaxed);
    PEAK.store(held, Ordering::Relaxed);
    let started = Instant::now();
    IN_CASE.store(true, Ordering::Relaxed);
    let result = std::panic::catch_unwind(|| {
        ImportedBody::load(dir.join(spec).to_str().expect("UTF-8 scratch path"))
            .map(|_| ())
            .map_err(|e| e.to_string())
    });
    IN_CASE.store(false, Ordering::Relaxed);
    let elapsed = started.elapsed();
    let peak = PEAK.load(Ordering::Relaxed).saturating_sub(held);
    if elapsed > CASE_TIME {
        return Err(format!("took {elapsed:.1?} (bound {CASE_TIME:?})"));
    }
    if peak > CASE_MEMORY {
        return Err(format!("held {peak} bytes at once (bound {CASE_MEMORY})"));
    }
    match result {
        Err(panic) => {
            let text = panic
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Err(format!("panicked: {text}"))
        }
        Ok(Ok(())) => Ok(Outcome::Loaded),
        Ok(Err(message)) => {
            if message.trim().is_empty() {
                return Err("an empty error message".into());
            }
            // `file:LINE:` of the mutated file names a line it has.
            let name = Path::new(mutated).file_name().unwrap().to_string_lossy();
            let needle = format!("{name}:");
            if let Some(at) = message.find(&needle) {
                let rest = &message[at + needle.len()..];
                let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
                if let Ok(line) = digits.parse::<usize>()
                    && rest[digits.len()..].starts_with(':')
                    && !(1..=lines + 1).contains(&line)
                {
                    return Err(format!(
                        "names line {line} of a {lines}-line file: {message}"
                    ));
                }
            }
            Ok(Outcome::Named(message))
        }
    }
}

/// Runs `seeds` over every target: per seed one target, one of its files, one mutation.
fn run(seeds: Vec<u64>) {
    let targets = targets();
    assert!(targets.len() >= 10, "{} body specs", targets.len());
    let formats = [
        "mtx", "rua", "pch", "op4", "mapping", "sti", "mas", "dof", "csv", "toml",
    ];
    for f in formats {
        assert!(
            targets.iter().any(|t| t
                .files
                .iter()
                .any(|n| n.trim_end_matches(".gz").ends_with(f))),
            "no committed body has a `{f}` file to mutate"
        );
    }
    // One scratch copy of each folder; a case writes its mutated file there and restores it.
    let scratch = Scratch::new("fuzz");
    let copies: Vec<PathBuf> = targets
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let copy = scratch.join(format!("{i}"));
            std::fs::create_dir_all(&copy).unwrap();
            for f in &t.files {
                std::fs::copy(t.dir.join(f), copy.join(f)).unwrap();
            }
            copy
        })
        .collect();
    let (mut loaded, mut named, mut failures) = (0usize, 0usize, Vec::new());
    let mut by_file = std::collections::BTreeMap::<String, usize>::new();
    let mut originals = std::collections::HashMap::<(usize, String), Vec<u8>>::new();
    let started = Instant::now();
    for &seed in &seeds {
        let mut rng = Rng::new(seed);
        let t = rng.below(targets.len());
        let target = &targets[t];
        let file = &target.files[rng.below(target.files.len())];
        // Decompressed once per file: the largest committed bodies' matrices are ~10 MB.
        let original = originals
            .entry((t, file.clone()))
            .or_insert_with(|| plain(&target.dir.join(file)));
        let (bytes, what) = mutate(original, &mut rng);
        let lines = bytes.split(|&b| b == b'\n').count();
        let case = format!(
            "seed {seed}: {}/{} with {file}: {what}",
            target
                .dir
                .strip_prefix(env!("CARGO_MANIFEST_DIR"))
                .unwrap()
                .display(),
            target.spec
        );
        // Printed before the case runs: an abort leaves it as the last line.
        eprintln!("{case}");
        let path = copies[t].join(file);
        std::fs::write(&path, &bytes).unwrap();
        let outcome = load_case(&copies[t], &target.spec, file, lines);
        std::fs::copy(target.dir.join(file), &path).unwrap();
        *by_file
            .entry(
                file.trim_end_matches(".gz")
                    .rsplit('.')
                    .next()
                    .unwrap()
                    .to_string(),
            )
            .or_default() += 1;
        match outcome {
            Ok(Outcome::Loaded) => loaded += 1,
            Ok(Outcome::Named(message)) => {
                named += 1;
                eprintln!("  -> {}", message.lines().next().unwrap_or(""));
            }
            Err(problem) => failures.push(format!("FAILED {case}\n  {problem}")),
        }
    }
    println!(
        "{} cases (seeds {}..={}) in {:.1} s: {named} named errors, {loaded} loads, {} failures; \
         cases per kind of file: {by_file:?}",
        seeds.len(),
        seeds.first().unwrap_or(&0),
        seeds.last().unwrap_or(&0),
        started.elapsed().as_secs_f64(),
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{} of the cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn a_hundred_mutated_body_files_load_or_give_named_errors() {
    run((0..QUICK_CASES).collect());
}

/// The thorough set; `FLEXMODES_FUZZ_SEEDS=821,1370` replays those seeds alone, and
/// `FLEXMODES_FUZZ_SHARD=2/3` runs every third seed from the second on (CI runs one process
/// per core: the counting allocator measures one case at a time per process).
#[test]
#[ignore = "thousands of cases: CI runs them (`cargo test --test fuzz_readers -- --ignored`)"]
fn thousands_of_mutated_body_files_load_or_give_named_errors() {
    let seeds: Vec<u64> = match std::env::var("FLEXMODES_FUZZ_SEEDS") {
        Ok(list) => list
            .split(',')
            .map(|s| {
                s.trim()
                    .parse()
                    .expect("FLEXMODES_FUZZ_SEEDS: comma-separated seeds")
            })
            .collect(),
        Err(_) => (QUICK_CASES..QUICK_CASES + THOROUGH_CASES).collect(),
    };
    let seeds = match std::env::var("FLEXMODES_FUZZ_SHARD") {
        Ok(shard) => {
            let (i, n) = shard
                .split_once('/')
                .and_then(|(i, n)| Some((i.parse::<usize>().ok()?, n.parse::<usize>().ok()?)))
                .filter(|&(i, n)| (1..=n).contains(&i))
                .expect("FLEXMODES_FUZZ_SHARD: I/N with 1 <= I <= N");
            seeds.into_iter().skip(i - 1).step_by(n).collect()
        }
        Err(_) => seeds,
    };
    run(seeds);
}

/// Every file under `tests/fuzz/regressions/` replaces its namesake in the body its
/// `regressions.toml` entry names; each must give a named error (or load) in bounds.
#[test]
fn every_regression_file_gives_a_named_error() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = root.join("tests/fuzz/regressions");
    let manifest: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join("regressions.toml")).unwrap()).unwrap();
    assert!(!manifest.is_empty());
    for (file, entry) in &manifest {
        let body = root.join(entry["body"].as_str().unwrap());
        let spec = entry["spec"].as_str().unwrap();
        let replaces = entry["replaces"].as_str().unwrap();
        let expect = entry["error"].as_str().unwrap();
        let scratch = Scratch::new("fuzz-regression");
        for e in std::fs::read_dir(&body).unwrap() {
            let e = e.unwrap();
            if e.path().is_file() {
                std::fs::copy(e.path(), scratch.join(e.file_name())).unwrap();
            }
        }
        let bytes = std::fs::read(dir.join(file)).unwrap();
        std::fs::write(scratch.join(replaces), &bytes).unwrap();
        let lines = bytes.split(|&b| b == b'\n').count();
        match load_case(&scratch, spec, replaces, lines) {
            Ok(Outcome::Named(message)) => assert!(
                message.contains(expect),
                "{file}: `{message}` does not say `{expect}`"
            ),
            Ok(Outcome::Loaded) => panic!("{file}: loaded; expected `{expect}`"),
            Err(problem) => panic!("{file}: {problem}"),
        }
    }
}

/// The `.npy` reader (the exports' Ψ, read back by tests and users' scripts) on 2 000
/// mutations of a written array: an array or `None`, never a panic or an allocation beyond
/// [`CASE_MEMORY`].
#[test]
fn mutated_npy_files_read_or_are_refused() {
    let a = faer::Mat::<f64>::from_fn(37, 5, |i, j| (i * 5 + j) as f64 - 20.0);
    let scratch = Scratch::new("fuzz-npy");
    flexmodes::body_file::write_npy(&scratch.join("a.npy"), a.as_ref()).unwrap();
    let bytes = std::fs::read(scratch.join("a.npy")).unwrap();
    let (mut read, mut refused) = (0, 0);
    for seed in 0..2_000u64 {
        let mut rng = Rng::new(seed);
        let (mutated, what) = mutate(&bytes, &mut rng);
        IN_CASE.store(true, Ordering::Relaxed);
        let outcome = std::panic::catch_unwind(|| flexmodes::body_file::read_npy(&mutated));
        IN_CASE.store(false, Ordering::Relaxed);
        match outcome {
            Ok(Some((rows, cols, values))) => {
                assert_eq!(rows * cols, values.len(), "seed {seed}: {what}");
                read += 1;
            }
            Ok(None) => refused += 1,
            Err(_) => panic!("seed {seed}: read_npy panicked on {what}"),
        }
    }
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}
