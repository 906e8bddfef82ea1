//! The text and JSON of a simulation bench: the points' table, the stability checks, and the
//! cost of one evaluation of the equations of motion against the model's coordinates.

use serde_json::{Map, Value, json};

use super::bench_point::{
    ABOVE_CRITICAL, BELOW_CRITICAL, BenchPoint, LOOSE_ATOL, LOOSE_RTOL, STABILITY_RUN_S,
};
use crate::{
    dynamics::{IntegrationScheme, IntegratorParameters, imaginary_stability_limit},
    report::{markdown_table, sig},
};

/// Coordinates of a point's system: the frame's six and the modal ones.
fn coordinates(p: &BenchPoint) -> usize {
    6 + p.dofs
}

/// The least-squares line µs = fixed + per · coordinates through the points of one
/// integrator setting (`label`, as [`BenchPoint::integrator_label`]), with their count; `None`
/// with fewer than two distinct sizes.
pub(super) fn evaluation_cost_fit(points: &[BenchPoint], label: &str) -> Option<(f64, f64, usize)> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.integrator_label() == label && p.evaluations > 0)
        .map(|p| (coordinates(p) as f64, p.us_per_evaluation))
        .collect();
    let n = xy.len() as f64;
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / n,
        xy.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx).powi(2)).sum();
    if xy.len() < 2 || sxx == 0.0 {
        return None;
    }
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let per = sxy / sxx;
    Some((my - per * mx, per, xy.len()))
}

/// The integrator settings of `points`, in their order of appearance.
fn labels(points: &[BenchPoint]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for p in points {
        let l = p.integrator_label();
        if !out.contains(&l) {
            out.push(l);
        }
    }
    out
}

fn evaluation_cost_json(points: &[BenchPoint]) -> Value {
    let fits: Map<String, Value> = labels(points)
        .into_iter()
        .filter_map(|l| {
            evaluation_cost_fit(points, &l).map(|(fixed, per, count)| {
                (
                    l,
                    json!({ "fixed_us": sig(fixed), "us_per_coordinate": sig(per), "points": count }),
                )
            })
        })
        .collect();
    Value::Object(fits)
}

/// The per-evaluation table and its fitted fixed part.
fn evaluation_cost_text(points: &[BenchPoint]) -> String {
    let rows: Vec<Vec<String>> = points
        .iter()
        .map(|p| {
            vec![
                p.method.id().into(),
                p.integrator_label(),
                p.modes.to_string(),
                coordinates(p).to_string(),
                p.evaluations.to_string(),
                format!("{:.2}", p.us_per_evaluation),
            ]
        })
        .collect();
    let fits: Vec<String> = labels(points)
        .into_iter()
        .filter_map(|l| {
            evaluation_cost_fit(points, &l).map(|(fixed, per, count)| {
                format!("{l}: {fixed:.2} µs + {per:.3} µs per coordinate ({count} points)")
            })
        })
        .collect();
    format!(
        "\n\nThe cost of one evaluation of the equations of motion (the online wall time over \
         the evaluations: every stage, Newton iteration and finite difference, the steps' and \
         projections' own work shared among them; one thread), against the coordinates (the \
         frame's six and the modal ones). A least-squares line through each integrator's \
         points gives the part every evaluation pays whatever the model's size, and the part \
         each coordinate adds: {}.\n\n{}",
        fits.join("; "),
        markdown_table(
            &[
                "method",
                "integrator",
                "modes",
                "coordinates",
                "evaluations",
                "µs per evaluation"
            ],
            &rows,
        )
    )
}

/// The points' table rows; the speed-up is against the first point (NR).
pub(super) fn point_rows(points: &[BenchPoint]) -> Vec<Vec<String>> {
    let nr_online = points[0].online_s_per_sim_s;
    points
        .iter()
        .map(|p| {
            vec![
                p.method.id().into(),
                p.integrator_label(),
                p.modes.to_string(),
                p.dofs.to_string(),
                format!("{}", flexmodes_core::report::readable(p.offline_s, 3)),
                format!("{:.3}", p.online_s_per_sim_s),
                format!("{:.1}", nr_online / p.online_s_per_sim_s),
                format!("{:.4}", p.rel_rms_error),
                p.steps.to_string(),
                if p.pareto { "★" } else { "" }.to_string(),
            ]
        })
        .collect()
}

/// The bench as JSON: every point and the stability checks per model.
pub(super) fn bench_json(
    scene: &str,
    dofs: usize,
    points: &[BenchPoint],
    stability: Map<String, Value>,
) -> Value {
    json!({
        "scene": scene,
        "dofs": dofs,
        "points": points.iter().map(|p| json!({
            "method": p.method.id(),
            "modes": p.modes,
            "dofs": p.dofs,
            "offline_s": sig(p.offline_s),
            "online_s_per_sim_s": sig(p.online_s_per_sim_s),
            "rel_rms_error": sig(p.rel_rms_error),
            "steps": p.steps,
            "evaluations": p.evaluations,
            "us_per_evaluation": sig(p.us_per_evaluation),
            "integrator": p.integrator.id(),
            "rtol": p.rtol,
            "pareto": p.pareto,
        })).collect::<Vec<_>>(),
        "stability": Value::Object(stability),
        "evaluation_cost": evaluation_cost_json(points),
    })
}

/// The bench's text: how it measured, the points' table and the stability table.
pub(super) fn bench_text(
    schemes: &[IntegrationScheme],
    repeats: usize,
    rows: &[Vec<String>],
    stability_rows: &[Vec<String>],
    points: &[BenchPoint],
) -> String {
    let y_star = imaginary_stability_limit();
    let defaults = IntegratorParameters::default();
    let (scene_rtol, scene_atol, output_ms) =
        (defaults.rtol, defaults.atol, defaults.output_interval * 1e3);
    format!(
        "Errors are node 8's mean relative RMS against the full model integrated by {}; online \
     cost is the median of {repeats} runs; speed-up is against the first row. `dp5` runs \
     at the scenes' tolerances (rtol {scene_rtol}, atol {scene_atol}), `dp5 rtol \
     {LOOSE_RTOL}` at rtol {LOOSE_RTOL}, atol {LOOSE_ATOL}: there the error \
     control no longer binds and the step grows to the stability bound (or to the \
     {output_ms} ms output interval), \
     which is where a reduced model's lower highest frequency buys an explicit scheme \
     fewer steps. ★ marks the Pareto front: no other point is both faster \
     online and more accurate (errors equal to three digits count as equal).\n\n{}\nUndamped modes sit on the imaginary axis, where Dormand-Prince 5(4) keeps \
     |R(iωh)| ≤ 1 only for ωh ≤ {y_star:.3} (beyond it the growth per step stays below \
     1e-4 up to ωh ≈ 1.1, so at the scenes' tolerances the error control, not stability, \
     sets the step). \
     `stability.<method>.critical_dt_s` = {y_star:.3} / ω_max of the reduced model held \
     by the nodal-fixed frame: Guyan's and the full model's stiff high modes bound the \
     step most. Checked by fixed-step runs without error control, at {BELOW_CRITICAL}× \
     the critical step over {STABILITY_RUN_S} s (must stay bounded) and at \
     {ABOVE_CRITICAL}× over the whole interval (must diverge, `Error::Diverged`). The \
     implicit generalized-α scheme is unconditionally stable for linear systems; the last \
     column runs it with the step that breaks the explicit one \
     (`stability.<method>.implicit_above_bounded`; FAILED: it diverged or its Newton \
     iterations did not converge, a named error). Reduction buys the implicit scheme \
     cheaper steps, not larger ones:\n\n{}",
        schemes[0].name(),
        markdown_table(
            &[
                "method",
                "integrator",
                "modes",
                "DOF",
                "offline s",
                "online s per sim s",
                "speed-up vs NR",
                "rel. RMS error",
                "steps",
                "Pareto",
            ],
            rows,
        ),
        markdown_table(
            &[
                "method",
                "highest Hz",
                "critical step s",
                &format!("{BELOW_CRITICAL}× step"),
                &format!("{ABOVE_CRITICAL}× step"),
                &format!("gen-alpha at {ABOVE_CRITICAL}×"),
            ],
            stability_rows,
        ),
        scene_rtol = flexmodes_core::report::readable(scene_rtol, 1),
        scene_atol = flexmodes_core::report::readable(scene_atol, 1),
        LOOSE_RTOL = flexmodes_core::report::readable(LOOSE_RTOL, 1),
        LOOSE_ATOL = flexmodes_core::report::readable(LOOSE_ATOL, 1)
    ) + &evaluation_cost_text(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reduction::Method;

    fn point(dofs: usize, us: f64, scheme: IntegrationScheme) -> BenchPoint {
        BenchPoint {
            method: Method::CraigBampton,
            modes: 0,
            dofs,
            offline_s: 0.0,
            online_s_per_sim_s: 1.0,
            rel_rms_error: 0.0,
            steps: 1,
            evaluations: 1,
            us_per_evaluation: us,
            integrator: scheme,
            rtol: None,
            pareto: false,
        }
    }

    /// The fit recovers a line through exact points, per integrator setting, and refuses a
    /// single size.
    #[test]
    fn the_evaluation_cost_fit_recovers_its_line() {
        let ga = IntegrationScheme::GeneralizedAlpha {
            spectral_radius: 0.8,
        };
        let mut points: Vec<BenchPoint> = [8, 12, 30, 84]
            .iter()
            .map(|&d| {
                point(
                    d,
                    2.0 + 0.25 * (6 + d) as f64,
                    IntegrationScheme::DormandPrince,
                )
            })
            .collect();
        points.push(point(12, 7.0, ga));
        let (fixed, per, count) = evaluation_cost_fit(&points, "dp5").unwrap();
        assert!((fixed - 2.0).abs() < 1e-12 && (per - 0.25).abs() < 1e-12 && count == 4);
        assert!(evaluation_cost_fit(&points, "gen-alpha").is_none());
        let text = evaluation_cost_text(&points);
        assert!(
            text.contains("dp5: 2.00 µs + 0.250 µs per coordinate (4 points)"),
            "{text}"
        );
    }
}
