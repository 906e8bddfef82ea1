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

use crate::dynamics::DynamicsError;
use crate::record::{REFERENCE, method_color};
use crate::reduction::ReductionError;
use serde_json::{Value, json};

use super::{SceneInfo, SceneOptions, SceneOutput};
use crate::{
    Error, Result,
    fem::{BeamParameters, FeModel, SlabParameters, beam, slab},
    models::{
        ABOVE_CRITICAL, BELOW_CRITICAL, BELOW_RUN_S, KEPT_MODES, MOVED_NODE, boundary_motion,
        condensation_cost, eitelberg_feedback, explicit_step, guyan_mean_axes, guyan_symmetry,
        too_few_boundary,
    },
    record::{Geometry, Layout, LogLogChart, LogLogSeries, Visual},
    reduction::Method,
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
            Box::new(|| Ok(too_few_boundary_failure(&slab_model))),
        ),
        (
            "eitelberg_without_feedback",
            "Eitelberg without the feedback trick",
            Box::new(|| eitelberg_failure(&beam_model)),
        ),
        (
            "mode_condensation_cost",
            "mode condensation's cost",
            Box::new(condensation_failure),
        ),
        (
            "mean_axes_guyan_mass",
            "mean axes with a Guyan mass",
            Box::new(|| guyan_mean_axes_failure(&slab_model)),
        ),
        (
            "explicit_above_critical",
            "explicit step above critical",
            Box::new(|| explicit_step_failure(&slab_model, opts)),
        ),
        (
            "guyan_b_symmetry",
            "Guyan (b)'s symmetry",
            Box::new(|| guyan_symmetry_failure(&beam_model)),
        ),
        (
            "modal_truncation_boundary",
            "modal truncation and boundary motion",
            Box::new(|| boundary_motion_failure(&slab_model)),
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
fn too_few_boundary_failure(model: &FeModel) -> Failure {
    let mut cases = Vec::new();
    let mut said = Vec::new();
    for case in too_few_boundary(model) {
        let nodes = case.nodes;
        match case.outcome {
            Err(
                e @ Error::Reduction(ReductionError::SingularInterior {
                    rank_deficiency, ..
                }),
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
fn eitelberg_failure(model: &FeModel) -> Result<Failure> {
    let study = eitelberg_feedback(model)?;
    let with = &study.with_hz;
    let (json, what) = match study.without {
        Err(e @ Error::Reduction(ReductionError::UnstableSystem { max_real_part })) => (
            json!({
                "error": "UnstableSystem",
                "max_real_part": max_real_part,
                "message": e.to_string(),
                "with_feedback_hz": sig_vec(with),
            }),
            format!(
                "`UnstableSystem`: largest real part of A's eigenvalues {max_real_part:.1e} \
                 (rigid-body poles at 0, undamped poles on the imaginary axis); with L = [I I] \
                 it reduces and gives {:.4} Hz",
                with.first().copied().unwrap_or(f64::NAN)
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

/// Offline time of mode condensation and Craig–Bampton on refined slabs, charted.
fn condensation_failure() -> Result<Failure> {
    let cost = condensation_cost()?;
    let (dofs, mc_s, cb_s) = (&cost.dofs, &cost.mc_s, &cost.cb_s);
    let (mc_exp, cb_exp) = (cost.exponent(mc_s), cost.exponent(cb_s));
    let n = dofs.len() - 1;
    let series = |id: &str, label: &str, m: Method, times: &[f64]| LogLogSeries {
        id: id.into(),
        label: label.into(),
        color: method_color(m),
        points: dofs.iter().map(|&d| d as f64).zip(times.to_vec()).collect(),
        line: true,
    };
    let chart = LogLogChart {
        path: "charts/cost".into(),
        x_unit: "DOF".into(),
        y_unit: "s".into(),
        series: vec![
            series("mc", "MC (complete eigen)", Method::ModeCondensation, mc_s),
            series("cb", "CB (6 modes)", Method::CraigBampton, cb_s),
        ],
        x_linear: false,
    };
    let max_angle = cost.max_angle;
    Ok(Failure {
        json: json!({
            "dofs": dofs,
            "interior_dofs": cost.interior,
            "mc_s": sig_vec(mc_s),
            "cb_s": sig_vec(cb_s),
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
fn guyan_mean_axes_failure(model: &FeModel) -> Result<Failure> {
    let g = guyan_mean_axes(model)?;
    Ok(Failure {
        json: json!({
            "masters": g.masters,
            "block_anisotropy": {"lumped": g.anisotropy_lumped, "guyan": sig(g.anisotropy_guyan)},
            "identity_defect": {"lumped": g.identity_full, "guyan": sig(g.identity_guyan)},
            "coupling_rel_error": sig(g.coupling_error),
        }),
        line: [
            "Mean axes with a Guyan-condensed mass matrix (slab, masters 16, 18, 28, 30, 5, 11)"
                .into(),
            format!(
                "the condensed M's 3×3 nodal blocks are {:.0} % anisotropic (lumped: \
                 {:.0e}); δ̇̃ᵀMδ̇ for two modes' velocities is {:.1} % of its \
                 scale (full body: {:.0e}); the deformation term δ̃ᵀMδ̇ of the \
                 angular mean-axis condition is off by {:.0} %",
                100.0 * g.anisotropy_guyan,
                g.anisotropy_lumped,
                100.0 * g.identity_guyan,
                g.identity_full,
                100.0 * g.coupling_error
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

/// slab-sim1 with Craig–Bampton: fixed Dormand–Prince steps below and above the critical
/// step; the critical steps of NR, GR, MT and CB beside it.
fn explicit_step_failure(model: &FeModel, opts: &SceneOptions) -> Result<Failure> {
    let study = explicit_step(model, &opts.progress)?;
    let critical = study.critical;
    let below_ok = study.below.is_ok();
    let (above_diverged, above_text) = match &study.above {
        Some(e @ Error::Dynamics(DynamicsError::Diverged { .. })) => (true, e.to_string()),
        Some(e) => (false, e.to_string()),
        None => (false, "no divergence".into()),
    };
    let below_zeta = *study.below.as_ref().unwrap_or(&f64::NAN);
    let mut histories = Vec::new();
    if let Some(points) = study.below_history {
        histories.push((
            format!("{BELOW_CRITICAL}× critical"),
            method_color(Method::CraigBampton),
            points,
        ));
    }
    if let Some(points) = study.above_history {
        histories.push((
            format!("{ABOVE_CRITICAL}× critical"),
            [230, 90, 60, 255],
            points,
        ));
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
    let predicted_json: serde_json::Map<String, Value> = study
        .predicted
        .iter()
        .map(|p| {
            (
                p.method.id().to_string(),
                json!({
                    "coordinates": p.coordinates,
                    "highest_hz": sig(p.highest_hz),
                    "critical_dt_s": sig(p.critical_s),
                }),
            )
        })
        .collect();
    let nr = study.predicted[0];
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
                nr.critical_s,
                nr.highest_hz,
                critical / nr.critical_s
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

/// Guyan (a) and (b) on the beam: symmetry of the first elastic mode, drawn side by side.
fn guyan_symmetry_failure(model: &FeModel) -> Result<Failure> {
    let style = |id: &str| match id {
        "full" => ("full model", REFERENCE),
        "guyan_a" => ("Guyan (a) 1, 3, 5", method_color(Method::Guyan)),
        _ => ("Guyan (b) 1, 2, 5", [230, 90, 60, 255]),
    };
    let mut defects = serde_json::Map::new();
    let mut hz_json = serde_json::Map::new();
    let mut visuals = Vec::new();
    let mut said = Vec::new();
    let geometry = standing(&Geometry::of(model).nodes);
    for (k, case) in guyan_symmetry(model)?.iter().enumerate() {
        let (name, color) = style(case.id);
        let (hz, defect) = (case.hz, case.defect);
        defects.insert(case.id.to_string(), json!(sig(defect)));
        hz_json.insert(case.id.to_string(), json!(sig(hz)));
        said.push(format!("{name} {defect:.1e} at {hz:.4} Hz"));
        let path = format!("modes/beam_{}/1", case.id);
        visuals.push(Visual::Offset {
            path: path.clone(),
            translation: [1.3 * model.size() * k as f64, 0.0, 0.0],
        });
        let shape = super::mode_visuals::display_shape(model, &case.mode);
        visuals.push(Visual::Mode {
            path,
            geometry: Geometry {
                nodes: geometry.clone(),
                strips: Geometry::of(model).strips,
            },
            shape: standing(&shape),
            label: format!("{name}: {hz:.4} Hz, mirror defect {defect:.1e}"),
            color,
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
fn boundary_motion_failure(model: &FeModel) -> Result<Failure> {
    let study = boundary_motion(model)?;
    // Drawn at one common scale: the exact response's largest displacement at 15 % of the
    // slab's size.
    let largest = study
        .exact
        .chunks(3)
        .map(|d| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt())
        .fold(0.0f64, f64::max);
    let scale = 0.15 * model.size() / largest;
    let geometry = Geometry::of(model);
    let mut visuals = Vec::new();
    for (k, (id, name, u, color)) in [
        ("exact", "exact (full model)", &study.exact, REFERENCE),
        (
            "mt",
            "modal truncation",
            &study.mt,
            method_color(Method::ModalTruncation),
        ),
        (
            "cb",
            "Craig–Bampton",
            &study.cb,
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
    let (mt_error, cb_error, ratio) = (study.mt_error, study.cb_error, study.mt_energy_ratio);
    Ok(Failure {
        json: json!({
            "moved": format!("node {MOVED_NODE} z"),
            "rel_error": {"mt": sig(mt_error), "cb": cb_error},
            "mt_energy_ratio": sig(ratio),
        }),
        line: [
            "Modal truncation and boundary motion (slab held at 16, 18, 28, 30)".into(),
            format!(
                "static response to a displacement of node {MOVED_NODE} (z): modal \
                 truncation's best response is {:.0} % off (strain energy {ratio:.1}× \
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
