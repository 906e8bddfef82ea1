//! The failures scene's cases of reduction, each computed and drawn: too few boundary DOF for
//! Craig–Bampton, Eitelberg without feedback, mode condensation's cost, Guyan (b)'s symmetry.

use crate::record::{REFERENCE, method_color};
use crate::reduction::ReductionError;
use crate::{
    Result,
    error::CoreError,
    fem::FeModel,
    models::{condensation_cost, eitelberg_feedback, guyan_symmetry, too_few_boundary},
    record::{Geometry, LogLogChart, LogLogSeries, Visual},
    reduction::Method,
    report::{sig, sig_vec},
};
use serde_json::{Value, json};

/// One failure's report entry, panel line and visuals.
pub(super) struct Failure {
    pub(super) json: Value,
    pub(super) line: [String; 3],
    pub(super) visuals: Vec<Visual>,
}

/// Craig–Bampton on the slab with one corner and with two corners as the boundary.
pub(super) fn too_few_boundary_failure(model: &FeModel) -> Failure {
    let mut cases = Vec::new();
    let mut said = Vec::new();
    for case in too_few_boundary(model) {
        let nodes = case.nodes;
        match case.outcome {
            Err(
                e @ CoreError::Reduction(ReductionError::SingularInterior {
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
pub(super) fn eitelberg_failure(model: &FeModel) -> Result<Failure> {
    let study = eitelberg_feedback(model)?;
    let with = &study.with_hz;
    let (json, what) = match study.without {
        Err(e @ CoreError::Reduction(ReductionError::UnstableSystem { max_real_part })) => (
            json!({
                "error": "UnstableSystem",
                "max_real_part": max_real_part,
                "message": e.to_string(),
                "with_feedback_hz": sig_vec(with),
            }),
            format!(
                "`UnstableSystem`: largest real part of A's eigenvalues {max_real_part} \
                 (rigid-body poles at 0, undamped poles on the imaginary axis); with L = [I I] \
                 it reduces and gives {:.4} Hz",
                with.first().copied().unwrap_or(f64::NAN),
                max_real_part = flexmodes_core::report::readable(max_real_part, 2)
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
pub(super) fn condensation_failure() -> Result<Failure> {
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
        y_unit: "wall time, s".into(),
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
                 (largest principal angle {max_angle} rad)",
                dofs[n],
                mc_s[n],
                cb_s[n],
                mc_s[n] / cb_s[n],
                max_angle = flexmodes_core::report::readable(max_angle, 2)
            ),
            "Eq. 6.29 condenses every deleted interior mode, so it needs the complete interior \
             eigenproblem (~n³); Craig–Bampton computes only the kept modes and one \
             factorisation of K_ii"
                .into(),
        ],
        visuals: chart.visuals(),
    })
}

/// Guyan (a) and (b) on the beam: symmetry of the first elastic mode, drawn side by side.
pub(super) fn guyan_symmetry_failure(model: &FeModel) -> Result<Failure> {
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
        said.push(format!(
            "{name} {defect} at {hz:.4} Hz",
            defect = flexmodes_core::report::readable(defect, 2)
        ));
        let path = format!("modes/beam_{}/1", case.id);
        visuals.push(Visual::Offset {
            path: path.clone(),
            translation: [1.3 * model.size() * k as f64, 0.0, 0.0],
        });
        let shape = crate::scenes::mode_visuals::display_shape(model, &case.mode);
        visuals.push(Visual::Mode {
            path,
            geometry: Geometry {
                nodes: geometry.clone(),
                strips: Geometry::of(model).strips,
            },
            shape: standing(&shape),
            label: format!(
                "{name}: {hz:.4} Hz, mirror defect {defect}",
                defect = flexmodes_core::report::readable(defect, 2)
            ),
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
pub(super) fn standing(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    points.iter().map(|p| [p[0], -p[2], p[1]]).collect()
}
