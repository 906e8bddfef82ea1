//! The substructure tree of the refined slab, level by level: how many parts, how large the
//! separators and leaves are, and what a multi-level elimination over it holds (each node's
//! front: its own unknowns and the ancestors' unknowns its subtree touches, dense). The
//! factor's size from the fronts is checked against faer's symbolic analysis of the same
//! order where that is affordable.
//!
//! With `--cutoff HZ`, AMLS's first level too: every leaf's fixed-interface modes below the
//! cut-off ([`flexmodes_core::linalg::leaf_modes`]), timed on `--threads N` (default: all).
//!
//! With `--amls WANTED` as well, the lowest `WANTED` free-free pairs by AMLS over the whole
//! tree ([`flexmodes_core::linalg::amls_lowest_modes`], every node keeping its modes below the
//! cut-off, then refined) beside flexmodes' Lanczos ([`flexmodes_core::reduction::free_body_pairs`])
//! in the same run: times, peak memory, and the largest difference of their frequencies
//! (`--guard N`: pairs carried beside the wanted ones through AMLS's refinement).
//!
//! ```sh
//! cargo run --release --example substructure_tree -- 24x12x6 50x25x12 --leaf 2000
//! cargo run --release --example substructure_tree -- 40x20x10 --leaf 2000 --cutoff 60
//! cargo run --release --example substructure_tree -- 40x20x10 --leaf 500 --cutoff 8 --amls 50
//! ```

use std::time::Instant;

use flexmodes_core::{
    fem::{FeModel, SlabParameters, slab},
    linalg::{
        AmlsEigenParameters, AmlsParameters, LeafModesParameters, SubstructureTree, SymbolicFactor,
        amls_lowest_modes, leaf_modes, machine_threads, negative_shift, nested_dissection,
        peak_resident_bytes, reset_peak_resident, set_threads,
    },
    reduction::{FreeBodyParameters, free_body_pairs},
};

/// The command line's settings (see the module's documentation).
struct Options {
    sizes: Vec<[usize; 3]>,
    leaf: usize,
    check_up_to: usize,
    cutoff: Option<f64>,
    amls: Option<usize>,
    guard: usize,
    threads: usize,
}

fn options() -> Options {
    let mut sizes = Vec::new();
    let mut leaf = 2000;
    let mut check_up_to = 200_000;
    let mut cutoff = None;
    let mut amls = None;
    let mut guard = AmlsEigenParameters::default().guard;
    let mut threads = machine_threads();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--leaf" => leaf = args.next().and_then(|s| s.parse().ok()).expect("--leaf N"),
            "--cutoff" => cutoff = args.next().and_then(|s| s.parse::<f64>().ok()),
            "--amls" => amls = args.next().and_then(|s| s.parse::<usize>().ok()),
            "--guard" => guard = args.next().and_then(|s| s.parse().ok()).expect("--guard N"),
            "--threads" => {
                threads = args
                    .next()
                    .and_then(|s| s.parse().ok())
                    .expect("--threads N")
            }
            "--check-up-to" => {
                check_up_to = args
                    .next()
                    .and_then(|s| s.parse().ok())
                    .expect("--check-up-to N")
            }
            size => {
                let b: Vec<usize> = size
                    .split('x')
                    .map(|s| s.parse().expect("NXxNYxNZ"))
                    .collect();
                assert_eq!(b.len(), 3, "NXxNYxNZ");
                sizes.push([b[0], b[1], b[2]]);
            }
        }
    }
    Options {
        sizes,
        leaf,
        check_up_to,
        cutoff,
        amls,
        guard,
        threads,
    }
}

fn main() {
    let mut options = options();
    // The threads' pool is built once per process: one count per run.
    options.threads = set_threads(Some(options.threads));
    if options.sizes.is_empty() {
        options.sizes = vec![[24, 12, 6], [40, 20, 10]];
    }
    for &bricks in &options.sizes {
        report_size(bricks, &options);
        println!();
    }
}

/// The tree, fronts and factors of the slab meshed with `bricks`, and AMLS's first level and
/// comparison with Lanczos where asked.
fn report_size(bricks: [usize; 3], options: &Options) {
    let (leaf, check_up_to, threads) = (options.leaf, options.check_up_to, options.threads);
    let (cutoff, amls, guard) = (options.cutoff, options.amls, options.guard);
    let started = Instant::now();
    let model = slab(&SlabParameters::refined(bricks).expect("a slab"));
    let n = model.dof_count();
    let assembled = started.elapsed().as_secs_f64();
    let k = model.k.as_faer();
    let tree = model.substructure_tree(leaf).expect("coordinates");
    let nodes = tree.nodes();
    let mut front_entries = 0f64;
    let mut largest_front = 0usize;
    let mut per_level: Vec<(usize, usize, usize, usize)> = vec![(0, 0, 0, 0); tree.levels()];
    // Each node's boundary: the ancestors' unknowns coupled to its subtree.
    let bsize: Vec<usize> = tree.boundaries(&[k]).iter().map(|b| b.len()).collect();
    for (j, node) in nodes.iter().enumerate() {
        let s = node.unknowns.len() as f64;
        front_entries += s * (s + 1.0) / 2.0 + s * bsize[j] as f64;
        largest_front = largest_front.max(node.unknowns.len() + bsize[j]);
        let e = &mut per_level[node.level];
        e.0 += 1;
        e.1 += node.unknowns.len();
        e.2 = e.2.max(node.unknowns.len());
        e.3 = e.3.max(bsize[j]);
    }
    let built = started.elapsed().as_secs_f64() - assembled;
    println!(
        "slab {}×{}×{} bricks: {n} DOF, {} tree nodes over {} levels (leaves ≤ {leaf}); \
         assembled in {assembled:.1} s, tree and fronts in {built:.1} s",
        bricks[0],
        bricks[1],
        bricks[2],
        nodes.len(),
        tree.levels()
    );
    println!("| level | nodes | unknowns | largest node | largest boundary |");
    println!("|---|---|---|---|---|");
    for (level, (count, unknowns, largest, bnd)) in per_level.iter().enumerate() {
        println!("| {level} | {count} | {unknowns} | {largest} | {bnd} |");
    }
    println!(
        "factor from the fronts (dense within each node): {:.3e} entries, {:.2} GB; the \
         largest front {largest_front} unknowns, {:.2} GB dense",
        front_entries,
        front_entries * 8.0 / 1e9,
        (largest_front as f64).powi(2) * 8.0 / 1e9
    );
    if n <= check_up_to {
        let symbolic = SymbolicFactor::analyse_ordered(k, Some(&tree.order())).expect("analysis");
        println!(
            "faer's supernodal factor of the same order: {:.3e} entries ({:.2} of the fronts'), \
             {:.2} GB, {:.3e} flops to factor",
            symbolic.factor_nnz() as f64,
            symbolic.factor_nnz() as f64 / front_entries,
            symbolic.factor_nnz() as f64 * 8.0 / 1e9,
            symbolic.flops()
        );
        // The order the Lanczos solvers factor with (free_body_pairs, the interior).
        let order = nested_dissection(k, &model.dof_positions());
        let symbolic = SymbolicFactor::analyse_ordered(k, order.as_deref()).expect("analysis");
        println!(
            "faer's factor under the eigensolvers' nested dissection: {:.3e} entries \
             ({:.0} per DOF), {:.2} GB, {:.3e} flops to factor",
            symbolic.factor_nnz() as f64,
            symbolic.factor_nnz() as f64 / n as f64,
            symbolic.factor_nnz() as f64 * 8.0 / 1e9,
            symbolic.flops()
        );
    }
    if let Some(hz) = cutoff {
        report_leaves(&model, &tree, hz, threads);
    }
    if let (Some(hz), Some(wanted)) = (cutoff, amls) {
        compare_amls_and_lanczos(&model, &tree, hz, wanted, guard, threads);
    }
}

/// AMLS's first level below `hz`: the modes its leaves keep, their worst residual, the time.
fn report_leaves(model: &FeModel, tree: &SubstructureTree, hz: f64, threads: usize) {
    let started = Instant::now();
    let leaves = leaf_modes(
        &model.k,
        &model.m,
        tree,
        hz,
        &LeafModesParameters::default(),
    )
    .expect("leaf modes");
    let kept: usize = leaves.iter().map(|l| l.modes.values.len()).sum();
    let most = leaves
        .iter()
        .map(|l| l.modes.values.len())
        .max()
        .unwrap_or(0);
    let worst = leaves
        .iter()
        .map(|l| l.modes.max_residual())
        .fold(0.0f64, f64::max);
    println!(
        "AMLS's first level below {hz} Hz: {} leaves keep {kept} modes (at most {most} \
         a leaf; each count equal to its leaf's inertia), worst residual {worst:.1e}, \
         {:.2} s on {threads} thread(s)",
        leaves.len(),
        started.elapsed().as_secs_f64()
    );
}

/// The lowest `wanted` free-free pairs by AMLS (cut-off `hz`) and by Lanczos, timed one after
/// the other, each with its own peak resident memory.
fn compare_amls_and_lanczos(
    model: &flexmodes_core::fem::FeModel,
    tree: &SubstructureTree,
    hz: f64,
    wanted: usize,
    guard: usize,
    threads: usize,
) {
    let gb = |b: Option<u64>| b.map_or(f64::NAN, |b| b as f64 / 1e9);
    let params = AmlsEigenParameters {
        reduction: AmlsParameters {
            cutoff_hz: hz,
            shift: negative_shift(&model.k, &model.m),
            ..AmlsParameters::default()
        },
        guard,
        ..AmlsEigenParameters::default()
    };
    let rigid = model.rigid_body_modes();
    reset_peak_resident();
    let started = Instant::now();
    let (amls, stats) = amls_lowest_modes(
        &model.k,
        &model.m,
        tree,
        wanted,
        Some(rigid.as_ref()),
        &params,
    )
    .expect("AMLS");
    let amls_s = started.elapsed().as_secs_f64();
    let amls_peak = gb(peak_resident_bytes());
    println!(
        "AMLS, {wanted} pairs, first cut-off {hz} Hz: {amls_s:.2} s, peak {amls_peak:.2} GB on \
         {threads} thread(s); {} reduction(s), the last at {:.1} Hz keeping {} modes, block \
         factor {:.3e} entries; reductions {:.2} s, projected \
         solve {:.2} s, refinement {:.2} s ({} refinement steps, worst residual {:.1e} before, \
         {:.1e} after; eigenvalues {:.1e} apart before), Sturm {:.2} s (missed {})",
        stats.reductions,
        stats.cutoff_hz,
        stats.projected,
        stats.factor_entries as f64,
        stats.seconds[0],
        stats.seconds[1],
        stats.seconds[2],
        stats.iterations,
        stats.unrefined_residual,
        stats.max_residual,
        stats.unrefined_value_error,
        stats.seconds[3],
        amls.sturm.map_or(0, |s| s.missed())
    );
    reset_peak_resident();
    let started = Instant::now();
    let lanczos = free_body_pairs(model, wanted, &FreeBodyParameters::default()).expect("Lanczos");
    let lanczos_s = started.elapsed().as_secs_f64();
    let lanczos_peak = gb(peak_resident_bytes());
    let worst = amls.elastic_values_apart(&lanczos);
    println!(
        "Lanczos, {wanted} pairs: {lanczos_s:.2} s, peak {lanczos_peak:.2} GB; AMLS / Lanczos \
         {:.2}; largest relative difference of the elastic eigenvalues {worst:.1e}; highest {:.4} Hz",
        amls_s / lanczos_s,
        lanczos.hz().last().copied().unwrap_or(0.0)
    );
}
