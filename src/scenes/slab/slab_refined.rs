//! `slab-modes --refine NX,NY,NZ`: the App. B slab (same 4 × 2 × 1 m body, material and mass)
//! meshed with NX × NY × NZ bricks, reduced on the sparse path, with the cost of each phase.

use crate::reduction::{ReductionRequest, reduce, reduce_interior};
use std::time::Instant;

use serde_json::{Map, Value, json};

use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    frequency_bars::{FrequencyBars, SHOWN_MODES},
    mode_visuals::undeformed,
};
use crate::{
    Error, Result,
    analysis::{elastic_hz, lowest_free_free_modes, reduced_modes},
    fem::{FeModel, SlabParameters, slab},
    linalg::{GeneralizedEigen, check_reduction_memory, peak_resident_bytes},
    record::{Layout, Visual},
    reduction::{
        Basis, InteriorProblem, Method, ModeCondensationRoute, ModeSelection, ReductionStatistics,
        SolverPath,
    },
    report::{Report, Table, fmt_hz, sig, sig_vec},
};

const AVAILABLE: [Method; 4] = [
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
    Method::Guyan,
];
/// Kept normal modes unless `--modes` says otherwise (as on the App. B slab).
/// Fixed-interface frequencies reported at least (the benchmark's 20).
const REPORTED_FIXED_INTERFACE: usize = 20;
/// Elastic free-free modes computed and drawn.
const FREE_FREE: usize = 6;
/// §7.2.1's extra Guyan masters, nodes 5 and 11 of App. B, as positions (m) on the top face.
const EXTRA_GUYAN_MASTER_POSITIONS: [[f64; 3]; 2] = [[1.0, 1.0, 1.0], [3.0, 1.0, 1.0]];

/// Runs `slab-modes` (described by `info`) on a mesh of `bricks`.
pub fn run(opts: &SceneOptions, info: &SceneInfo, bricks: [usize; 3]) -> Result<SceneOutput> {
    refuse_axes(opts, info)?;
    let params = SlabParameters::refined(bricks)?;
    let dofs = params.dof_count();
    // Refuse before allocating anything a mesh the machine cannot hold.
    let needed = check_reduction_memory(dofs)?;
    let methods = opts.methods_or(info.name, &AVAILABLE, &AVAILABLE)?;
    let boundary = opts
        .boundary
        .clone()
        .unwrap_or_else(|| params.bottom_corners().to_vec());
    let kept = opts.modes_or_default(info);
    let gr_masters = guyan_masters(&params, &boundary);

    opts.progress.phase("assembly")?;
    let started = Instant::now();
    let model = slab(&params);
    let assembly_s = started.elapsed().as_secs_f64();
    // The Craig-Bampton work of the benchmark: one factorisation of K_ii, the constraint modes
    // and the lowest fixed-interface modes; MT and MC reuse both.
    let started = Instant::now();
    let mut problem = InteriorProblem::new(&model, &boundary, SolverPath::Auto)?
        .with_progress(opts.progress.clone());
    let fi = problem.kept_modes(ModeSelection::Count(kept.max(REPORTED_FIXED_INTERFACE)))?;
    let cb = reduce_interior(
        &mut problem,
        &ReductionRequest::of(Method::CraigBampton).modes(ModeSelection::Count(kept)),
    )?;
    let reduction_s = started.elapsed().as_secs_f64();
    let phases = problem.statistics;
    let fixed_interface_hz = fi.hz();
    let mut visuals = vec![undeformed(&model)];
    let mut bars = FrequencyBars::new(SHOWN_MODES);
    let run = RefinedRun {
        model: &model,
        kept,
        gr_masters: &gr_masters,
        cb: &cb,
        reduction_s,
    };
    let MethodResults {
        reduced,
        sizes,
        method_s,
        rows,
    } = reduce_methods(&run, &methods, &mut problem, &mut bars, opts)?;
    opts.progress.phase("free-free modes")?;
    let ff = lowest_free_free_modes(&model, FREE_FREE)?;
    let free_free_hz = elastic_hz(&ff);
    bars.push_first(Method::NoReduction, &free_free_hz);
    visuals.extend(bars.visuals());
    let peak = peak_resident_bytes();
    let mut report = Report::new(info.name);
    insert_parameters(&mut report, bricks, &boundary, &run, &methods);
    let r = &mut report.results;
    super::slab_mode_results::insert_mode_results(
        r,
        (&free_free_hz, &fixed_interface_hz),
        reduced,
        sizes,
    );
    r.insert("total_mass_kg".into(), json!(sig(model.total_mass())));
    r.insert("dofs".into(), json!(dofs));
    r.insert("nnz".into(), json!(model.stiffness_nnz()));
    insert_phases(r, &phases, assembly_s, reduction_s);
    r.insert("method_time_s".into(), Value::Object(method_s));
    r.insert("peak_memory_bytes".into(), json!(peak));
    r.insert("estimated_memory_bytes".into(), json!(needed));
    report.table = format!(
        "Refined slab {}×{}×{} bricks: {dofs} DOF, {} stiffness entries, {} in the Cholesky \
         factor of K_ii ({} path). Boundary {boundary:?}, {kept} kept modes, GR masters \
         {gr_masters:?}.\n\nCraig-Bampton work (s): assembly {assembly_s:.3}, factorisation \
         {:.3}, constraint modes {:.3}, eigen ({} fixed-interface modes) {:.3}, reduction in \
         all {reduction_s:.3}; peak memory {}.\n\n{}\nFixed-interface: {}\n\nFree-free \
         elastic: {}\n",
        bricks[0],
        bricks[1],
        bricks[2],
        model.stiffness_nnz(),
        phases.factor_nnz,
        if phases.sparse { "sparse" } else { "dense" },
        phases.factorization_s,
        phases.constraint_modes_s,
        fixed_interface_hz.len(),
        phases.eigen_s,
        peak.map_or("unknown".into(), |b| format!("{:.0} MB", b as f64 / 1e6)),
        report.add_table(Table::from_text(
            &["model", "lowest elastic Hz", "s"],
            &rows
        )),
        fmt_hz(&fixed_interface_hz[..fixed_interface_hz.len().min(8)]),
        fmt_hz(&free_free_hz),
    );
    let markdown = scene_text(bricks, &bars.caption(), &report.table);

    let (mode_visuals, layout) = mode_views(&model, &mut problem, (&fi, &ff), kept, bars.layout())?;
    visuals.extend(mode_visuals);
    Ok(SceneOutput::new(report, markdown, visuals, layout).on_timeline("phase"))
}

/// What every method of a refined run shares: the slab, the kept modes, Guyan's masters, and
/// Craig–Bampton's basis with the time it took.
struct RefinedRun<'a> {
    model: &'a FeModel,
    kept: usize,
    gr_masters: &'a [usize],
    cb: &'a Basis,
    reduction_s: f64,
}

/// Each method's reduced frequencies, basis size and time (by method id), and its table row.
struct MethodResults {
    reduced: Map<String, Value>,
    sizes: Map<String, Value>,
    method_s: Map<String, Value>,
    rows: Vec<Vec<String>>,
}

/// The run's mesh, boundary, Guyan masters, kept modes and methods into `report`.
fn insert_parameters(
    report: &mut Report,
    bricks: [usize; 3],
    boundary: &[usize],
    run: &RefinedRun<'_>,
    methods: &[Method],
) {
    let p = &mut report.parameters;
    p.insert("refine".into(), json!(bricks));
    p.insert("boundary".into(), json!(boundary));
    p.insert("guyan_masters".into(), json!(run.gr_masters));
    p.insert("modes".into(), json!(run.kept));
    p.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
}

/// Reduces the slab by every method of `methods` (their frequencies into `bars`).
fn reduce_methods(
    run: &RefinedRun<'_>,
    methods: &[Method],
    problem: &mut InteriorProblem,
    bars: &mut FrequencyBars,
    opts: &SceneOptions,
) -> Result<MethodResults> {
    let dofs = run.model.dof_count();
    let mut reduced = Map::new();
    let mut sizes = Map::new();
    let mut method_s = Map::new();
    let mut rows = Vec::new();
    for &m in methods {
        let started = Instant::now();
        let basis = refined_basis(m, run, problem, opts)?;
        let elapsed = if m == Method::CraigBampton {
            run.reduction_s
        } else {
            started.elapsed().as_secs_f64()
        };
        method_s.insert(m.id().into(), json!(sig(elapsed)));
        let hz = elastic_hz(&reduced_modes(run.model, &basis)?);
        reduced.insert(m.id().into(), json!(sig_vec(&hz)));
        sizes.insert(m.id().into(), json!([basis.psi.nrows(), basis.psi.ncols()]));
        rows.push(vec![
            format!("{} ({dofs} × {})", m.id().to_uppercase(), basis.size()),
            fmt_hz(&hz[..hz.len().min(6)]),
            format!("{elapsed:.3}"),
        ]);
        bars.push(m, &hz);
    }
    Ok(MethodResults {
        reduced,
        sizes,
        method_s,
        rows,
    })
}

/// The mode views of the refined slab: its free-free (`ff`), constraint and fixed-interface
/// (`fi`) modes in tabs above the frequency `chart`.
fn mode_views(
    model: &FeModel,
    problem: &mut InteriorProblem,
    (fi, ff): (&GeneralizedEigen, &GeneralizedEigen),
    kept: usize,
    chart: Layout,
) -> Result<(Vec<Visual>, Layout)> {
    let (shapes, labels) = problem
        .constraint_shapes(crate::scenes::slab::slab_mode_views::MAX_DRAWN_CONSTRAINT_MODES)?;
    let (mode_visuals, layout) = crate::scenes::slab::slab_mode_views::slab_mode_views(
        crate::scenes::slab::slab_mode_views::ModeViews {
            model,
            part: &problem.partition,
            constraint: &shapes,
            constraint_labels: &labels,
            fixed_interface: fi,
            free_free: ff,
            shown_free_free: FREE_FREE,
            kept,
            first_tab: "fixed_interface",
            charts: vec![chart],
        },
    );
    Ok((mode_visuals, layout))
}

/// `--axes` is the App. B slab's alone.
fn refuse_axes(opts: &SceneOptions, info: &SceneInfo) -> Result<()> {
    if opts.axes.is_some() {
        return Err(Error::InvalidOption {
            option: "--axes",
            scene: Some(info.name),
            reason: "--axes is offered on the App. B slab only (its nodal-fixed nodes 16, 28, \
                     18 are not defined on a refined mesh)"
                .into(),
        });
    }
    Ok(())
}

/// The Guyan masters: the boundary and the nodes nearest App. B's extra masters.
fn guyan_masters(params: &SlabParameters, boundary: &[usize]) -> Vec<usize> {
    let mut masters = boundary.to_vec();
    for p in EXTRA_GUYAN_MASTER_POSITIONS {
        let node = params.nearest_node(p);
        if !masters.contains(&node) {
            masters.push(node);
        }
    }
    masters
}

/// One method's basis on the refined slab: CB's (already computed), MT and MC from the same
/// interior problem, Guyan on its masters.
fn refined_basis(
    m: Method,
    run: &RefinedRun<'_>,
    problem: &mut InteriorProblem,
    opts: &SceneOptions,
) -> Result<Basis> {
    let RefinedRun {
        model,
        kept,
        gr_masters,
        cb,
        ..
    } = *run;
    match m {
        Method::CraigBampton => Ok(cb.clone()),
        Method::ModalTruncation => Ok(reduce_interior(
            problem,
            &ReductionRequest::of(Method::ModalTruncation).modes(ModeSelection::Count(kept)),
        )?),
        Method::ModeCondensation => {
            let route = ModeCondensationRoute::for_interior(problem.interior_dofs());
            Ok(reduce_interior(
                problem,
                &ReductionRequest::of(Method::ModeCondensation)
                    .modes(ModeSelection::Count(kept))
                    .route(route),
            )?)
        }
        _ => {
            opts.progress.phase("Guyan reduction")?;
            Ok(reduce(
                model,
                &ReductionRequest::of(Method::Guyan)
                    .boundary(gr_masters)
                    .solver(SolverPath::Auto),
            )?)
        }
    }
}

/// The scene's text around its `table`.
fn scene_text(bricks: [usize; 3], caption: &str, table: &str) -> String {
    format!(
        "# slab-modes, refined\n\nThe App. B slab (4 × 2 × 1 m, E = 0.2e6 Pa, ν = 0.33, 62.4 \
         kg lumped equally per brick corner) meshed with {}×{}×{} trilinear bricks. The \
         interface defaults to the four bottom corners, nodes 16, 18, 28, 30 of App. B. K is \
         assembled sparse; Craig-Bampton factors K_ii once (sparse Cholesky, nested-dissection ordering), \
         takes the constraint modes as right-hand sides and the kept fixed-interface modes \
         from shift-invert block Lanczos on the same factor; MT and MC reuse both (MC from \
         the kept modes above {} interior DOF). Four point supports soften as the mesh \
         refines, so the fixed-interface frequencies do not converge; the free-free ones \
         converge from above. Views: the surface wireframe (grid lines thinned to at most 8 \
         per face), free-free modes, constraint modes and fixed-interface modes drawn on it. \
         {}\n\n{}",
        bricks[0],
        bricks[1],
        bricks[2],
        crate::reduction::MC_COMPLETE_ROUTE_LIMIT,
        caption,
        table
    )
}

/// The Craig–Bampton work's phases into the results: the factor's size and path, each phase's
/// time and the largest eigenpair residual.
fn insert_phases(
    r: &mut Map<String, Value>,
    phases: &ReductionStatistics,
    assembly_s: f64,
    reduction_s: f64,
) {
    r.insert("factor_nnz".into(), json!(phases.factor_nnz));
    r.insert("sparse".into(), json!(phases.sparse));
    r.insert(
        "timing_s".into(),
        json!({
            "assembly": sig(assembly_s),
            "factorization": sig(phases.factorization_s),
            "constraint_modes": sig(phases.constraint_modes_s),
            "eigen": sig(phases.eigen_s),
            "reduction": sig(reduction_s),
        }),
    );
    r.insert(
        "eigen_max_residual".into(),
        json!(phases.eigen_max_residual),
    );
}
