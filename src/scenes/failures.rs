//! `failures`: where each method fails, in one recording: a named error or a measured effect
//! per failure, with what went wrong and why.
//!
//! - Craig–Bampton with too few (or badly placed) boundary DOF: $K_{ii}$ singular (§6.4).
//! - Eitelberg without the output-feedback trick: the undamped $A$ is not stable (§6.6, App. C).
//! - Mode condensation's complete interior eigenproblem: n³ cost for CB's space (§6.5).
//! - Mean axes with a Guyan-condensed mass matrix: the condensed $M$ no longer commutes with
//!   rotations (Eq. 3.26) and $\dot{\tilde\delta}^T M \dot\delta \ne 0$ (Eq. 4.17).
//! - An explicit step above the critical one diverges (§7.2's models, Dormand–Prince 5(4)).
//! - Guyan (b)'s master choice breaks the beam's symmetry (§6.2.1).
//! - Modal truncation cannot carry boundary motion into the body (§6.3, §7.1).

use std::time::Instant;

use faer::Mat;
use serde_json::{Value, json};

use super::{
    SceneInfo, SceneOptions, SceneOutput,
    mode_visuals::{REFERENCE, method_color},
};
use crate::models::{
    PROBE_NODE, Scenario, default_boundary, probe_history, reduction_nodes, slab_body, slab_system,
};
use crate::{
    Error, Result,
    analysis::{
        StaticLoadCase, full_static_response, reduced_modes, relative_error, ritz_static_response,
    },
    dynamics::{AxisType, IntegratorParameters, critical_step, simulate},
    fem::{BeamParameters, FeModel, SlabParameters, beam, slab},
    linalg::principal_angles,
    record::{Geometry, Layout, LogLogChart, LogLogSeries, Visual},
    reduction::{
        Basis, EitelbergParameters, Method, ModeCondensationRoute, ModeSelection, NodalFixedAxes,
        SolverPath, craig_bampton, craig_bampton_on, eitelberg, guyan, modal_truncation,
        mode_condensation_route, no_reduction,
    },
    report::{Report, Table, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    id: "failures",
    summary: "where the methods fail, in one recording: CB with too few boundary DOF, \
              Eitelberg without feedback, mode condensation's n³ cost, mean axes with a \
              Guyan mass, an explicit step above critical, Guyan (b)'s symmetry, modal \
              truncation and boundary motion",
    sections: "§3.2, §4.2, §6.2–6.6, §7.1–7.2",
    controls: super::scene_info::SceneControls::methods_only(&[]),
};

/// Kept normal modes wherever a failure needs them (the §7.2 count).
const KEPT_MODES: usize = 6;
/// Boundary sets too small or badly placed for Craig–Bampton on the slab: one corner (3 DOF)
/// and two corners (6 DOF on one line: the rotation about it stays free).
const TOO_FEW_BOUNDARIES: [&[usize]; 2] = [&[16], &[16, 18]];
/// Meshes (bricks along x, y, z) of the cost comparison: 90 to 1 092 DOF (2 295 would add
/// ~6 s for MC alone to the main job).
const COST_MESHES: [[usize; 3]; 3] = [[4, 2, 1], [8, 4, 2], [12, 6, 3]];
/// The boundary DOF whose unit displacement modal truncation is asked to follow: node 30, z.
const MOVED_NODE: usize = 30;
/// Fixed steps of the explicit runs as multiples of the critical step (below: bounded, above:
/// Dormand–Prince grows 1.44× per step on the highest mode).
const BELOW_CRITICAL: f64 = 0.9;
const ABOVE_CRITICAL: f64 = 3.0;
/// Simulated interval of the run below the critical step, s.
const BELOW_RUN_S: f64 = 0.5;
/// Guyan (a)'s and (b)'s masters on the beam (§6.2.1).
const GUYAN_A: [usize; 3] = [1, 3, 5];
const GUYAN_B: [usize; 3] = [1, 2, 5];

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    opts.check_axes(INFO.id, &[])?;
    opts.methods_or(INFO.id, &[], &[])?;
    if opts.modes.is_some() || opts.boundary.is_some() || opts.end_time.is_some() {
        return Err(Error::InvalidOption {
            scene: INFO.id.into(),
            reason: "the failures scene has fixed settings (each failure states its own)".into(),
        });
    }
    let beam_model = beam(&BeamParameters::default());
    let slab_model = slab(&SlabParameters::default());
    let mut report = Report::new(INFO.id);
    let mut lines: Vec<[String; 3]> = Vec::new();
    let mut visuals = Vec::new();

    type Study<'a> = Box<dyn Fn() -> Result<Failure> + 'a>;
    let studies: [(&str, &str, Study); 7] = [
        (
            "craig_bampton_too_few_boundary",
            "Craig–Bampton with too few boundary DOF",
            Box::new(|| Ok(too_few_boundary(&slab_model))),
        ),
        (
            "eitelberg_without_feedback",
            "Eitelberg without the feedback trick",
            Box::new(|| eitelberg_without_feedback(&beam_model)),
        ),
        (
            "mode_condensation_cost",
            "mode condensation's cost",
            Box::new(mode_condensation_cost),
        ),
        (
            "mean_axes_guyan_mass",
            "mean axes with a Guyan mass",
            Box::new(|| guyan_mass_with_mean_axes(&slab_model)),
        ),
        (
            "explicit_above_critical",
            "explicit step above critical",
            Box::new(|| explicit_step(&slab_model, opts)),
        ),
        (
            "guyan_b_symmetry",
            "Guyan (b)'s symmetry",
            Box::new(|| guyan_b_symmetry(&beam_model)),
        ),
        (
            "modal_truncation_boundary",
            "modal truncation and boundary motion",
            Box::new(|| modal_truncation_boundary(&slab_model)),
        ),
    ];
    for (key, phase, study) in studies {
        opts.progress.phase(phase)?;
        let failure = study()?;
        report.results.insert(key.into(), failure.json);
        lines.push(failure.line);
        visuals.extend(failure.visuals);
    }

    report.table = report.add_table(Table::from_text(
        &["failure", "what happened (measured)", "why"],
        &lines.iter().map(|l| l.to_vec()).collect::<Vec<_>>(),
    ));
    // The panel is narrow: one section per failure instead of the three-column table.
    let sections: String = lines
        .iter()
        .enumerate()
        .map(|(k, [title, what, why])| {
            format!(
                "### {}. {title}\n\n**Measured.** {what}\n\n**Why.** {why}\n\n",
                k + 1
            )
        })
        .collect();
    let markdown = format!(
        "# failures\n\nEvery failure of the classical methods in one recording. Each is a \
         named error the program returns (and survives) or an effect measured here; the \
         report keys are under `results.<failure>` (`flexmodes report failures --json`).\n\n\
         **Views.** *guyan (b) symmetry*: the beam's first elastic mode, left to right: full \
         model (grey), Guyan (a) with masters 1, 3, 5, Guyan (b) with masters 1, 2, 5, \
         expanded to every node and turned into the x–z plane. *boundary motion*: the slab \
         held at nodes 16, 18, 28, 30 with node {MOVED_NODE} moved up; the exact static \
         response, modal truncation's best (Ritz) response and Craig–Bampton's, side by side \
         at one common scale. *cost*: offline time of mode condensation's complete interior \
         eigenproblem against Craig–Bampton's partial one, by mesh size (log–log). *explicit \
         step*: node 8's |ζ| in slab-sim1 with Craig–Bampton and fixed Dormand–Prince steps \
         below and above the critical one (log scale: the growth is a straight line).\n\n\
         {sections}"
    );
    let layout = Layout::Horizontal(
        vec![
            Layout::Vertical(
                vec![
                    Layout::Tabs(vec![
                        Layout::view3d("guyan (b) symmetry", "/modes"),
                        Layout::view3d("boundary motion", "/static"),
                    ]),
                    Layout::Horizontal(
                        vec![
                            Layout::Spatial2D {
                                name: "cost: offline s against DOF (log–log)".into(),
                                origin: "/charts/cost".into(),
                            },
                            Layout::Spatial2D {
                                name: "explicit step: node 8 |ζ| against time (semi-log)".into(),
                                origin: "/charts/explicit_step".into(),
                            },
                        ],
                        vec![1.0, 1.0],
                    ),
                ],
                vec![1.2, 1.0],
            ),
            Layout::scene_text(),
        ],
        vec![3.0, 2.0],
    );
    Ok(SceneOutput {
        report,
        markdown,
        visuals,
        layout,
        timeline: Some("phase".into()),
        y_up: false,
    })
}

/// One failure's report entry, panel line and visuals.
struct Failure {
    json: Value,
    line: [String; 3],
    visuals: Vec<Visual>,
}

/// Craig–Bampton on the slab with one corner and with two corners as the boundary.
fn too_few_boundary(model: &FeModel) -> Failure {
    let mut cases = Vec::new();
    let mut said = Vec::new();
    for nodes in TOO_FEW_BOUNDARIES {
        match craig_bampton(model, nodes, ModeSelection::Count(KEPT_MODES)) {
            Err(
                e @ Error::SingularInterior {
                    rank_deficiency, ..
                },
            ) => {
                said.push(format!(
                    "nodes {nodes:?} ({} DOF): `SingularInterior`, {rank_deficiency} rigid \
                     motion(s) free",
                    3 * nodes.len()
                ));
                cases.push(json!({
                    "boundary": nodes,
                    "error": "SingularInterior",
                    "rank_deficiency": rank_deficiency,
                    "message": e.to_string(),
                }));
            }
            other => {
                let what = match other {
                    Ok(_) => "no error".to_string(),
                    Err(e) => e.to_string(),
                };
                said.push(format!(
                    "nodes {nodes:?}: {what} (expected SingularInterior)"
                ));
                cases.push(json!({"boundary": nodes, "error": what}));
            }
        }
    }
    Failure {
        json: json!({ "cases": cases }),
        line: [
            "Craig–Bampton, too few boundary DOF (slab)".into(),
            said.join("; "),
            "K_ii must be invertible (Eq. 6.3): the boundary has to restrain all six rigid \
             motions — at least six DOF, not all on one line"
                .into(),
        ],
        visuals: Vec::new(),
    }
}

/// Eitelberg's reduction of the beam with and without the $L = [I\ I]$ feedback.
fn eitelberg_without_feedback(model: &FeModel) -> Result<Failure> {
    let without = eitelberg(
        model,
        &GUYAN_A,
        &EitelbergParameters {
            output_feedback: false,
        },
    );
    let with = eitelberg(model, &GUYAN_A, &EitelbergParameters::default())?;
    let (json, what) = match without {
        Err(e @ Error::UnstableSystem { max_real_part }) => (
            json!({
                "error": "UnstableSystem",
                "max_real_part": max_real_part,
                "message": e.to_string(),
                "with_feedback_hz": sig_vec(&with.hz),
            }),
            format!(
                "`UnstableSystem`: largest real part of A's eigenvalues {max_real_part:.1e} \
                 (rigid-body poles at 0, undamped poles on the imaginary axis); with L = [I I] \
                 it reduces and gives {:.4} Hz",
                with.hz.first().copied().unwrap_or(f64::NAN)
            ),
        ),
        Ok(_) => (
            json!({"error": "no error"}),
            "no error (expected UnstableSystem)".into(),
        ),
        Err(e) => (json!({"error": e.to_string()}), e.to_string()),
    };
    Ok(Failure {
        json,
        line: [
            "Eitelberg without the feedback trick (beam, masters 1, 3, 5)".into(),
            what,
            "App. C's Lyapunov equation needs an asymptotically stable A; a free, undamped \
             structure has none, so unit springs and dampers are added and removed afterwards \
             (§6.6.4)"
                .into(),
        ],
        visuals: Vec::new(),
    })
}

/// Offline time of mode condensation (complete interior eigenproblem, Eq. 6.29) and
/// Craig–Bampton (partial eigensolver) on refined slabs.
fn mode_condensation_cost() -> Result<Failure> {
    let mut dofs = Vec::new();
    let mut interior = Vec::new();
    let mut mc_s = Vec::new();
    let mut cb_s = Vec::new();
    let mut max_angle = 0.0f64;
    for bricks in COST_MESHES {
        let model = slab(&SlabParameters::refined(bricks)?);
        let boundary = default_boundary(&model);
        let start = Instant::now();
        let cb = craig_bampton_on(
            &model,
            &boundary,
            ModeSelection::Count(KEPT_MODES),
            SolverPath::Sparse,
        )?;
        cb_s.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        let mc = mode_condensation_route(
            &model,
            &boundary,
            ModeSelection::Count(KEPT_MODES),
            SolverPath::Sparse,
            ModeCondensationRoute::Complete,
        )?;
        mc_s.push(start.elapsed().as_secs_f64());
        let angles = principal_angles(mc.psi.as_ref(), cb.psi.as_ref())?;
        max_angle = angles.iter().copied().fold(max_angle, f64::max);
        dofs.push(model.dof_count());
        interior.push(model.dof_count() - 3 * boundary.len());
    }
    let exponent = |t: &[f64]| {
        let n = dofs.len();
        (t[n - 1] / t[n - 2]).ln() / (dofs[n - 1] as f64 / dofs[n - 2] as f64).ln()
    };
    let (mc_exp, cb_exp) = (exponent(&mc_s), exponent(&cb_s));
    let n = dofs.len() - 1;
    let chart = LogLogChart {
        path: "charts/cost".into(),
        x_unit: "DOF".into(),
        y_unit: "s".into(),
        series: vec![
            LogLogSeries {
                id: "mc".into(),
                label: "MC (complete eigen)".into(),
                color: method_color(Method::ModeCondensation),
                points: dofs.iter().map(|&d| d as f64).zip(mc_s.clone()).collect(),
                line: true,
            },
            LogLogSeries {
                id: "cb".into(),
                label: "CB (6 modes)".into(),
                color: method_color(Method::CraigBampton),
                points: dofs.iter().map(|&d| d as f64).zip(cb_s.clone()).collect(),
                line: true,
            },
        ],
        x_linear: false,
    };
    Ok(Failure {
        json: json!({
            "dofs": dofs,
            "interior_dofs": interior,
            "mc_s": sig_vec(&mc_s),
            "cb_s": sig_vec(&cb_s),
            "mc_exponent": sig(mc_exp),
            "cb_exponent": sig(cb_exp),
            "max_principal_angle_rad": max_angle,
        }),
        line: [
            "Mode condensation's cost (refined slabs)".into(),
            format!(
                "at {} DOF: MC {:.3} s against CB {:.3} s ({:.0}×); time grows as DOF^{mc_exp:.1} \
                 (CB DOF^{cb_exp:.1}) between the two largest meshes; both span one space \
                 (largest principal angle {max_angle:.1e} rad)",
                dofs[n],
                mc_s[n],
                cb_s[n],
                mc_s[n] / cb_s[n]
            ),
            "Eq. 6.29 condenses every deleted interior mode, so it needs the complete interior \
             eigenproblem (~n³); Craig–Bampton computes only the kept modes and one \
             factorisation of K_ii"
                .into(),
        ],
        visuals: chart.visuals(),
    })
}

/// The mass matrix of Guyan's masters as a nodal mass matrix under mean axes.
fn guyan_mass_with_mean_axes(model: &FeModel) -> Result<Failure> {
    // §7.2's Guyan masters: the four corners and App. B's nodes 5 and 11.
    let masters = reduction_nodes(model, Method::Guyan, &default_boundary(model));
    let g = guyan(model, &masters)?;
    // Columns node by node, x y z: the condensed model's nodes are the masters.
    for (c, col) in g.columns.iter().enumerate() {
        let expected = model.dofs_of_nodes(&[masters[c / 3]])?[c % 3];
        if col.dof != Some(expected) {
            return Err(Error::InvalidModeSelection {
                reason: format!("Guyan column {c} is not DOF {expected}"),
            });
        }
    }
    let m_g = g.reduced_mass(model);
    let m_full = model.m_dense();
    let anisotropy_guyan = block_anisotropy(&m_g);
    let anisotropy_lumped = block_anisotropy(&m_full);
    // Two elastic modes of the Guyan model, in master coordinates.
    let e = reduced_modes(model, &g)?;
    let elastic: Vec<usize> = (e.zero_energy..e.values.len()).take(2).collect();
    if elastic.len() < 2 {
        return Err(Error::TooManyModes {
            requested: 2,
            available: elastic.len(),
        });
    }
    let col = |j: usize| (0..e.vectors.nrows()).map(|i| e.vectors[(i, j)]).collect();
    let (a, b): (Vec<f64>, Vec<f64>) = (col(elastic[0]), col(elastic[1]));
    let v: Vec<f64> = a.iter().zip(&b).map(|(x, y)| x + y).collect();
    let expand = |z: &[f64]| -> Vec<f64> {
        (0..g.psi.nrows())
            .map(|i| (0..z.len()).map(|j| g.psi[(i, j)] * z[j]).sum())
            .collect()
    };
    // Eq. (4.17)'s dropped term: δ̇̃ᵀ M δ̇ (zero for a lumped or consistent M).
    let (h_g, scale_g) = skew_moment(&m_g, &v, &v);
    let (h_full, scale_full) = skew_moment(&m_full, &expand(&v), &expand(&v));
    let identity_guyan = norm3(h_g) / scale_g;
    let identity_full = norm3(h_full) / scale_full;
    // The deformation-dependent part of b̃ᵀMδ̇ (Eq. 4.15 with b = x + δ): δ̃ᵀ M δ̇ for
    // δ = mode 1, δ̇ = mode 2, condensed against the full body's.
    let (c_g, _) = skew_moment(&m_g, &a, &b);
    let (c_full, _) = skew_moment(&m_full, &expand(&a), &expand(&b));
    let coupling_error = norm3([c_g[0] - c_full[0], c_g[1] - c_full[1], c_g[2] - c_full[2]])
        / norm3(c_full).max(f64::MIN_POSITIVE);
    Ok(Failure {
        json: json!({
            "masters": masters,
            "block_anisotropy": {"lumped": anisotropy_lumped, "guyan": sig(anisotropy_guyan)},
            "identity_defect": {"lumped": identity_full, "guyan": sig(identity_guyan)},
            "coupling_rel_error": sig(coupling_error),
        }),
        line: [
            "Mean axes with a Guyan-condensed mass matrix (slab, masters 16, 18, 28, 30, 5, 11)"
                .into(),
            format!(
                "the condensed M's 3×3 nodal blocks are {:.0} % anisotropic (lumped: \
                 {anisotropy_lumped:.0e}); δ̇̃ᵀMδ̇ for two modes' velocities is {:.1} % of its \
                 scale (full body: {identity_full:.0e}); the deformation term δ̃ᵀMδ̇ of the \
                 angular mean-axis condition is off by {:.0} %",
                100.0 * anisotropy_guyan,
                100.0 * identity_guyan,
                100.0 * coupling_error
            ),
            "Eqs. 3.26 and 4.17 need M's nodal blocks to be multiples of I (lumped or \
             consistent) so that M commutes with rotations; a condensed M couples directions, \
             so mean axes imposed with it drift from the body's mean axes (measured here on \
             the terms, not by a simulation)"
                .into(),
        ],
        visuals: Vec::new(),
    })
}

/// Largest deviation of a nodal 3×3 block from a multiple of the identity, relative to the
/// largest block (Frobenius norms); 3 DOF per node, node by node.
fn block_anisotropy(m: &Mat<f64>) -> f64 {
    let nodes = m.nrows() / 3;
    let (mut worst, mut largest) = (0.0f64, 0.0f64);
    for i in 0..nodes {
        for j in 0..nodes {
            let b = |r: usize, c: usize| m[(3 * i + r, 3 * j + c)];
            let mean = (b(0, 0) + b(1, 1) + b(2, 2)) / 3.0;
            let (mut dev, mut all) = (0.0, 0.0);
            for r in 0..3 {
                for c in 0..3 {
                    let iso = if r == c { mean } else { 0.0 };
                    dev += (b(r, c) - iso).powi(2);
                    all += b(r, c).powi(2);
                }
            }
            worst = worst.max(dev.sqrt());
            largest = largest.max(all.sqrt());
        }
    }
    if largest > 0.0 { worst / largest } else { 0.0 }
}

/// $\sum_i a_i \times (M b)_i$ over 3-DOF nodes, and its scale $\sum_i |a_i|\,|(Mb)_i|$.
fn skew_moment(m: &Mat<f64>, a: &[f64], b: &[f64]) -> ([f64; 3], f64) {
    let mb: Vec<f64> = (0..m.nrows())
        .map(|i| (0..m.ncols()).map(|j| m[(i, j)] * b[j]).sum())
        .collect();
    let (mut h, mut scale) = ([0.0; 3], 0.0);
    for n in 0..a.len() / 3 {
        let p = [a[3 * n], a[3 * n + 1], a[3 * n + 2]];
        let q = [mb[3 * n], mb[3 * n + 1], mb[3 * n + 2]];
        h[0] += p[1] * q[2] - p[2] * q[1];
        h[1] += p[2] * q[0] - p[0] * q[2];
        h[2] += p[0] * q[1] - p[1] * q[0];
        scale += norm3(p) * norm3(q);
    }
    (h, scale.max(f64::MIN_POSITIVE))
}

fn norm3(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// slab-sim1 with Craig–Bampton: fixed Dormand–Prince steps below and above the critical
/// step; the critical steps of NR, GR, MT and CB beside it.
fn explicit_step(model: &FeModel, opts: &SceneOptions) -> Result<Failure> {
    let axes = AxisType::NodalFixed(NodalFixedAxes::slab_default());
    let boundary = default_boundary(model);
    let scenario = Scenario::HeldAtSix;
    let mut predicted = Vec::new();
    let mut cb_case = None;
    for (method, modes) in [
        (Method::NoReduction, 0),
        (Method::Guyan, 0),
        (Method::ModalTruncation, KEPT_MODES),
        (Method::CraigBampton, KEPT_MODES),
    ] {
        let body = slab_body(model, method, axes, &boundary, modes)?;
        let hz = reduced_modes(model, &body.basis)?.hz();
        let highest = hz.last().copied().unwrap_or(0.0);
        let critical = critical_step(2.0 * std::f64::consts::PI * highest);
        predicted.push((method, body.modes(), highest, critical));
        if method == Method::CraigBampton {
            cb_case = Some((body, critical));
        }
    }
    let (body, critical) = cb_case.expect("CB is in the list");
    let (system, state) = slab_system(&scenario, body)?;
    // Output at every step of the run above (no step is shortened to land on an output
    // time), so that it can be repeated up to just before its divergence.
    let fixed = |factor: f64, end: f64| {
        simulate(
            &system,
            &state,
            &IntegratorParameters {
                end_time: end,
                output_interval: if factor > 1.0 {
                    factor * critical
                } else {
                    end / 50.0
                },
                fixed_step: Some(factor * critical),
                ..Default::default()
            },
            &opts.progress,
        )
    };
    let below = fixed(BELOW_CRITICAL, BELOW_RUN_S);
    if let Err(Error::Cancelled) = below {
        return Err(Error::Cancelled);
    }
    let above = fixed(ABOVE_CRITICAL, scenario.end_time());
    if let Err(Error::Cancelled) = above {
        return Err(Error::Cancelled);
    }
    let below_ok = below.is_ok();
    let (above_diverged, above_text) = match &above {
        Err(e @ Error::Diverged { .. }) => (true, e.to_string()),
        Err(e) => (false, e.to_string()),
        Ok(_) => (false, "no divergence".into()),
    };
    let below_zeta = match &below {
        Ok(sim) => probe_history(&system, sim, PROBE_NODE)[2]
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs())),
        Err(_) => f64::NAN,
    };
    // The diverging run again, stopped a few steps before the state leaves the bound, so its
    // growth can be drawn: |ζ| of node 8 on a log scale against time.
    let mut histories = Vec::new();
    if let Ok(sim) = &below {
        histories.push((
            format!("{BELOW_CRITICAL}× critical"),
            method_color(Method::CraigBampton),
            zeta_history(&system, sim),
        ));
    }
    if let Err(Error::Diverged { time, .. }) = above {
        let h = ABOVE_CRITICAL * critical;
        let steps = ((time / h).floor() - 3.0).max(1.0);
        let run = simulate(
            &system,
            &state,
            &IntegratorParameters {
                end_time: steps * h,
                output_interval: h,
                fixed_step: Some(h),
                ..Default::default()
            },
            &opts.progress,
        );
        match run {
            Ok(sim) => histories.push((
                format!("{ABOVE_CRITICAL}× critical"),
                [230, 90, 60, 255],
                zeta_history(&system, &sim),
            )),
            Err(Error::Cancelled) => return Err(Error::Cancelled),
            Err(_) => {}
        }
    }
    let chart = LogLogChart {
        path: "charts/explicit_step".into(),
        x_unit: "s".into(),
        y_unit: "m".into(),
        series: histories
            .into_iter()
            .enumerate()
            .map(|(k, (label, color, points))| LogLogSeries {
                id: format!("run{}", k + 1),
                label,
                color,
                points,
                line: true,
            })
            .collect(),
        x_linear: true,
    };
    let predicted_json: serde_json::Map<String, Value> = predicted
        .iter()
        .map(|&(m, dofs, hz, dt)| {
            (
                m.id().to_string(),
                json!({"coordinates": dofs, "highest_hz": sig(hz), "critical_dt_s": sig(dt)}),
            )
        })
        .collect();
    let nr = predicted[0];
    Ok(Failure {
        json: json!({
            "scene": "slab-sim1",
            "method": "cb",
            "modes": KEPT_MODES,
            "critical_dt_s": sig(critical),
            "run_below_ok": below_ok,
            "run_above_diverged": above_diverged,
            "above_message": above_text,
            "below_max_zeta_m": sig(below_zeta),
            "predicted": predicted_json,
        }),
        line: [
            "Explicit step above critical (slab-sim1, CB 6 modes, DP5 fixed step)".into(),
            format!(
                "critical step {critical:.2e} s; at {BELOW_CRITICAL}× it runs {BELOW_RUN_S} s \
                 ({}); at {ABOVE_CRITICAL}×: {above_text}. NR's bound is {:.1e} s \
                 ({:.0} Hz), {:.0}× smaller",
                if below_ok { "bounded" } else { "FAILED" },
                nr.3,
                nr.2,
                critical / nr.3
            ),
            format!(
                "Dormand–Prince 5(4) is stable on the imaginary axis (undamped modes) only for \
                 ω·h ≤ {:.3}, so the highest retained frequency bounds the step; reduction \
                 lowers it (the full model keeps the stiff modes; at 3× the growth is 1.44× per \
                 step)",
                crate::dynamics::imaginary_stability_limit()
            ),
        ],
        visuals: chart.visuals(),
    })
}

/// $|\zeta|$ of node 8 against time, for a semi-log chart.
fn zeta_history(
    system: &crate::dynamics::System,
    sim: &crate::dynamics::Simulation,
) -> Vec<(f64, f64)> {
    let zeta = &probe_history(system, sim, PROBE_NODE)[2];
    sim.samples
        .iter()
        .zip(zeta)
        .map(|(s, z)| (s.t, z.abs()))
        .collect()
}

/// Distance of a beam displacement (2 DOF per node, x and y) from mirror symmetry about the
/// beam's middle: the smaller of its symmetric and antisymmetric defects, relative to its
/// largest entry.
fn mirror_defect(u: &[f64]) -> f64 {
    let nodes = u.len() / 2;
    let largest = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (mut sym, mut anti) = (0.0f64, 0.0f64);
    for i in 0..nodes {
        let j = nodes - 1 - i;
        // Mirror of (u_x, u_y) at x is (−u_x, u_y) at L − x.
        sym = sym
            .max((u[2 * i] + u[2 * j]).abs())
            .max((u[2 * i + 1] - u[2 * j + 1]).abs());
        anti = anti
            .max((u[2 * i] - u[2 * j]).abs())
            .max((u[2 * i + 1] + u[2 * j + 1]).abs());
    }
    sym.min(anti) / largest.max(f64::MIN_POSITIVE)
}

/// The first elastic mode of a basis on `model`, expanded to every DOF, and its frequency.
fn first_elastic_mode(model: &FeModel, basis: &Basis) -> Result<(Vec<f64>, f64)> {
    let e = reduced_modes(model, basis)?;
    let hz = e.hz();
    let j = (e.zero_energy < hz.len())
        .then_some(e.zero_energy)
        .ok_or(Error::TooManyModes {
            requested: 1,
            available: 0,
        })?;
    let u = (0..basis.psi.nrows())
        .map(|i| {
            (0..basis.size())
                .map(|c| basis.psi[(i, c)] * e.vectors[(c, j)])
                .sum()
        })
        .collect();
    Ok((u, hz[j]))
}

/// Guyan (a) and (b) on the beam: symmetry of the first elastic mode.
fn guyan_b_symmetry(model: &FeModel) -> Result<Failure> {
    let cases = [
        ("full", "full model", no_reduction(model), REFERENCE),
        (
            "guyan_a",
            "Guyan (a) 1, 3, 5",
            guyan(model, &GUYAN_A)?,
            method_color(Method::Guyan),
        ),
        (
            "guyan_b",
            "Guyan (b) 1, 2, 5",
            guyan(model, &GUYAN_B)?,
            [230, 90, 60, 255],
        ),
    ];
    let mut defects = serde_json::Map::new();
    let mut hz_json = serde_json::Map::new();
    let mut visuals = Vec::new();
    let mut said = Vec::new();
    let geometry = standing(&Geometry::of(model).nodes);
    for (k, (id, name, basis, color)) in cases.iter().enumerate() {
        let (u, hz) = first_elastic_mode(model, basis)?;
        let defect = mirror_defect(&u);
        defects.insert(id.to_string(), json!(sig(defect)));
        hz_json.insert(id.to_string(), json!(sig(hz)));
        said.push(format!("{name} {defect:.1e} at {hz:.4} Hz"));
        let path = format!("modes/beam_{id}/1");
        visuals.push(Visual::Offset {
            path: path.clone(),
            translation: [1.3 * model.size() * k as f64, 0.0, 0.0],
        });
        let shape = super::mode_visuals::display_shape(model, &u);
        visuals.push(Visual::Mode {
            path,
            geometry: Geometry {
                nodes: geometry.clone(),
                strips: Geometry::of(model).strips,
            },
            shape: standing(&shape),
            label: format!("{name}: {hz:.4} Hz, mirror defect {defect:.1e}"),
            color: *color,
        });
    }
    Ok(Failure {
        json: json!({"mirror_defect": defects, "hz": hz_json}),
        line: [
            "Guyan (b)'s broken symmetry (beam)".into(),
            format!("first elastic mode's mirror defect: {}", said.join("; ")),
            "masters 1, 2, 5 are not symmetric about the middle, so the condensed model and \
             its expanded modes are not either, and the frequency rises (§6.2.1)"
                .into(),
        ],
        visuals,
    })
}

/// A 2-D beam's (x, y) turned into the x–z plane, so the z-up views face it.
fn standing(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    points.iter().map(|p| [p[0], -p[2], p[1]]).collect()
}

/// Modal truncation and Craig–Bampton following a boundary displacement of the slab.
fn modal_truncation_boundary(model: &FeModel) -> Result<Failure> {
    let boundary = default_boundary(model);
    let modes = ModeSelection::Count(KEPT_MODES);
    // Every boundary DOF held, node 30 moved 1 m up, no load.
    let moved = model.dofs_of_nodes(&[MOVED_NODE])?[2];
    let case = StaticLoadCase {
        held: model
            .dofs_of_nodes(&boundary)?
            .into_iter()
            .map(|d| (d, if d == moved { 1.0 } else { 0.0 }))
            .collect(),
        load: vec![0.0; model.dof_count()],
    };
    let exact = full_static_response(model, &case)?;
    let mt = ritz_static_response(model, &modal_truncation(model, &boundary, modes)?, &case)?;
    let cb = ritz_static_response(model, &craig_bampton(model, &boundary, modes)?, &case)?;
    let error = |u: &[f64]| relative_error(u, &exact);
    let (mt_error, cb_error) = (error(&mt), error(&cb));
    // Strain energy of each response against the exact one (Ritz: never below it).
    let k = model.k_dense();
    let energy = |u: &[f64]| -> f64 {
        (0..u.len())
            .map(|i| u[i] * (0..u.len()).map(|j| k[(i, j)] * u[j]).sum::<f64>())
            .sum::<f64>()
    };
    let mt_energy_ratio = energy(&mt) / energy(&exact);
    // Drawn at one common scale: the exact response's largest displacement at 15 % of the
    // slab's size.
    let largest = exact
        .chunks(3)
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0f64, f64::max);
    let scale = 0.15 * model.size() / largest;
    let geometry = Geometry::of(model);
    let mut visuals = Vec::new();
    for (k, (id, name, u, color)) in [
        ("exact", "exact (full model)", &exact, REFERENCE),
        (
            "mt",
            "modal truncation",
            &mt,
            method_color(Method::ModalTruncation),
        ),
        (
            "cb",
            "Craig–Bampton",
            &cb,
            method_color(Method::CraigBampton),
        ),
    ]
    .into_iter()
    .enumerate()
    {
        let path = format!("static/{id}");
        visuals.push(Visual::Offset {
            path: path.clone(),
            translation: [0.0, -3.0 * k as f64, 0.0],
        });
        visuals.push(Visual::Mode {
            path,
            geometry: geometry.clone(),
            shape: u
                .chunks(3)
                .map(|d| [d[0] * scale, d[1] * scale, d[2] * scale])
                .collect(),
            label: format!("{name}: node {MOVED_NODE} moved up"),
            color,
        });
    }
    Ok(Failure {
        json: json!({
            "moved": format!("node {MOVED_NODE} z"),
            "rel_error": {"mt": sig(mt_error), "cb": cb_error},
            "mt_energy_ratio": sig(mt_energy_ratio),
        }),
        line: [
            "Modal truncation and boundary motion (slab held at 16, 18, 28, 30)".into(),
            format!(
                "static response to a displacement of node {MOVED_NODE} (z): modal \
                 truncation's best response is {:.0} % off (strain energy {mt_energy_ratio:.1}× \
                 the exact), Craig–Bampton's {cb_error:.0e}",
                100.0 * mt_error
            ),
            "MT's boundary columns move no interior node (Eq. 6.17), so boundary motion reaches \
             the body only through the kept fixed-interface modes; CB's constraint modes are \
             the exact static response (Eq. 6.3)"
                .into(),
        ],
        visuals,
    })
}
