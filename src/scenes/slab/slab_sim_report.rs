//! The slab simulations' report: what ran, node 8's errors against NR, each run's cost, and
//! the text around the table.

use serde_json::{Map, Value, json};

use crate::models::{PROBE_NODE, default_boundary, slab_node};
use crate::scenes::{SceneInfo, SceneOptions};
use crate::{
    analysis::{max_position_violation, relative_rms},
    dynamics::{AxisType, IntegrationScheme, IntegratorParameters, Simulation, System},
    fem::FeModel,
    reduction::Method,
    report::{Cell, Report, Table, sig},
};

/// Node 8's local directions, as entity paths and report keys name them.
pub(super) const DIRECTIONS: [&str; 3] = ["xi", "eta", "zeta"];

/// One run of a scenario: the method, its system and simulation (borrowed from the run cache)
/// and node 8's local deflection history along ξ, η, ζ.
pub(super) type Run<'a> = (Method, &'a System, &'a Simulation, [Vec<f64>; 3]);

/// Node 8's relative RMS errors against NR and each run's cost, into `report`'s results and
/// its table.
pub(super) fn errors_table(
    report: &mut Report,
    runs: &[Run],
    reference: Option<&[Vec<f64>; 3]>,
    params: &IntegratorParameters,
) {
    let mut errors = Map::new();
    let mut walls = Map::new();
    let mut table = Table::new(&[
        "method",
        "rel. RMS ξ",
        "rel. RMS η",
        "rel. RMS ζ",
        "coordinates",
        "wall s",
        if matches!(params.scheme, IntegrationScheme::DormandPrince) {
            "steps / rejected"
        } else {
            "steps / Newton its"
        },
        "max Φ violation",
    ])
    .rank_lower(&[1, 2, 3]);
    for (m, system, sim, hist) in runs {
        walls.insert(m.id().into(), json!(sig(sim.wall_time_s)));
        let mut e = Map::new();
        let mut cells = vec![Cell::text(m.id().to_uppercase())];
        if let Some(r) = reference {
            for a in 0..3 {
                let v = relative_rms(&hist[a], &r[a]);
                e.insert(DIRECTIONS[a].into(), json!(sig(v)));
                // NR is the reference: its zero is not ranked.
                cells.push(if *m == Method::NoReduction {
                    Cell::text(format!("{v:.4}"))
                } else {
                    Cell::number(v, format!("{v:.4}"))
                });
            }
            errors.insert(m.id().into(), Value::Object(e));
        } else {
            cells.extend([Cell::text("-"), Cell::text("-"), Cell::text("-")]);
        }
        let max_pos = max_position_violation(sim);
        cells.push(Cell::text(format!("{}", system.nv())));
        cells.push(Cell::number(
            sim.wall_time_s,
            format!("{:.3}", sim.wall_time_s),
        ));
        cells.push(Cell::text(match params.scheme {
            IntegrationScheme::DormandPrince => format!("{} / {}", sim.steps, sim.rejected),
            _ => format!("{} / {}", sim.steps, sim.newton_iterations),
        }));
        cells.push(Cell::number(
            max_pos,
            flexmodes_core::report::readable(max_pos, 2).to_string(),
        ));
        table.push(cells);
    }
    report
        .results
        .insert("rel_rms_error".into(), Value::Object(errors));
    report
        .results
        .insert("wall_time_s".into(), Value::Object(walls));
    report.table = report.add_table(table);
}

/// The scene's text: what was integrated and how, and the table.
pub(super) fn scenario_text(
    info: &SceneInfo,
    model: &FeModel,
    bricks: [usize; 3],
    params: &IntegratorParameters,
    opts: &SceneOptions,
    methods: usize,
    table: &str,
) -> String {
    let probe = slab_node(model, PROBE_NODE);
    format!(
        "# {}\n\n{}\n\nThe slab: {} bricks, {} DOF{}. Every method is integrated by {}, Euler \
         parameters renormalised and positions and velocities projected onto the \
         constraints after each step (velocities by the correction of least kinetic energy, \
         which no choice of basis changes), so differences come from the bases alone: CB and \
         MC span one space, and on the App. B slab their errors agree to 1e-4 in every \
         simulation and axis type. There, with the default explicit scheme, the NR \
         reference's own integration error (against a rerun at rtol 1e-10) stays at least 100 \
         times below the smallest error these tables print; tests check both. The implicit \
         generalized-α scheme is second order: its integration error falls fourfold when \
         --dt is halved, and at 0.25 ms it stays within 5e-4 of the explicit histories of \
         simulation 1 (tested). Coordinates are the six of the frame plus the modal ones. \
         Errors are \
         the relative RMS of node 8's local deflection against NR over the interval.{}{}\n\n{}",
        info.name,
        info.summary,
        bricks.map(|b| b.to_string()).join(" × "),
        model.dof_count(),
        if bricks == crate::scenes::slab::slab_modes::APP_B_BRICKS {
            " (App. B)".to_string()
        } else {
            format!(
                " (refined; nodes {} are App. B's 16, 18, 28, 30 and node {probe} is App. B's \
                 node 8, the top-face centre)",
                default_boundary(model)
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        },
        params.describe(),
        match opts.concurrent_integrations.min(methods) {
            0 | 1 => String::new(),
            n => format!(
                " The integrations ran up to {n} at a time, one thread each: a wall time is \
                 its own thread's (`flexmodes bench` times them one after the other)."
            ),
        },
        if opts.stiffening.unwrap_or(false) {
            " Dynamic stiffening is on: every model carries the geometric stiffness of its \
             frame's loads (the six products of the angular velocity, the angular \
             accelerations and the specific force, each solved statically on the held slab \
             and projected on its basis), which Lin's thesis leaves out; the thesis' numbers \
             are those without it."
        } else {
            " Dynamic stiffening is off, as in Lin's thesis (`--stiffening on` adds it): it \
             matters most in simulation 2, where the slab turns once per period of its orbit \
             (`slab-modes` gives the frequencies it turns against)."
        },
        table
    )
}

/// What a slab scenario runs with: its methods, the floating frame's axes, the kept modes,
/// the mesh (bricks along x, y, z), the boundary nodes (1-based) and the integrator.
#[derive(Debug, Clone, Copy)]
pub(super) struct ScenarioSettings<'a> {
    pub(super) methods: &'a [Method],
    pub(super) axes: AxisType,
    pub(super) modes: usize,
    pub(super) bricks: [usize; 3],
    pub(super) boundary: &'a [usize],
    pub(super) params: &'a IntegratorParameters,
}

/// What the scenario ran with, into `report`'s parameters.
pub(super) fn scenario_parameters(
    report: &mut Report,
    settings: &ScenarioSettings<'_>,
    model: &FeModel,
) {
    let ScenarioSettings {
        methods,
        axes,
        modes,
        bricks,
        boundary,
        params,
    } = *settings;
    report.parameters.insert("boundary".into(), json!(boundary));
    report.parameters.insert("modes".into(), json!(modes));
    report.parameters.insert("axes".into(), json!(axes.id()));
    report
        .parameters
        .insert("end_time_s".into(), json!(params.end_time));
    insert_integrator(report, params);
    report.parameters.insert("bricks".into(), json!(bricks));
    report
        .parameters
        .insert("dofs".into(), json!(model.dof_count()));
    report.parameters.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
}

/// The integrator a simulation ran with, in the report's parameters: `integrator` (`dp5` or
/// `gen-alpha`), `dt_s` (the fixed step, or null for adaptive steps) and, for generalized-α,
/// `rho_inf`.
pub fn insert_integrator(report: &mut Report, params: &IntegratorParameters) {
    report
        .parameters
        .insert("integrator".into(), json!(params.scheme.id()));
    report
        .parameters
        .insert("dt_s".into(), json!(params.step()));
    if let IntegrationScheme::GeneralizedAlpha { spectral_radius } = params.scheme {
        report
            .parameters
            .insert("rho_inf".into(), json!(spectral_radius));
    }
}
