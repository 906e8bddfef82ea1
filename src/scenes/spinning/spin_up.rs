//! `spin-up`: dynamic stiffening, the thesis' open problem (§1, refs. [16], [18]): the
//! rotating cantilever's Campbell diagram against the published tables, and Kane, Ryan &
//! Banerjee's (1987) spin-up against an independent geometrically nonlinear reference, each
//! by NR and CB with and without the geometric stiffness of the frame's loads.

use serde_json::json;

use crate::scenes::{SceneInfo, SceneOptions, SceneOutput};
use crate::{
    Result,
    fem::BendingPlane,
    models::{
        CampbellParameters, CampbellStudy, PUBLISHED_TOLERANCE, SPIN_UP_TOLERANCE,
        SpinUpParameters, SpinUpStudy, campbell_study, spin_up_reference, spin_up_study,
    },
    record::{Color, Layout, LogLogChart, LogLogSeries, REFERENCE, Visual, method_color},
    reduction::Method,
    report::{Cell, Report, Table, sig},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "spin-up",
    recording_cost: 2,
    summary: "dynamic stiffening (§1, refs. [16], [18]): the rotating cantilever's Campbell \
              diagram against Wright et al. (1982), and Kane et al.'s (1987) spin-up against a \
              co-rotational reference, NR and CB with and without stiffening",
    sections: "§1; Kane, Ryan & Banerjee 1987",
    controls: crate::scenes::scene_info::SceneControls {
        modes: Some(6),
        ..crate::scenes::scene_info::SceneControls::NONE
    },
};

/// The published speeds the tables are compared over (λ = 0…10).
const COMPARED_UP_TO: f64 = 10.0;

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let modes = opts.modes_or_default(&INFO).max(1);
    let campbell = campbell_study(&CampbellParameters {
        reduced_modes: modes,
        ..Default::default()
    })?;
    let spin = spin_up_study(
        &SpinUpParameters {
            reduced_modes: modes,
            ..Default::default()
        },
        &opts.progress,
    )?;
    let mut report = Report::new(INFO.name);
    let beam = &spin.parameters.beam;
    report.parameters.insert(
        "beam".into(),
        json!({"length_m": beam.length, "ei_n_m2": beam.bending_stiffness,
               "ea_n": beam.axial_stiffness, "rho_a_kg_m": beam.mass_per_length,
               "elements_spin_up": beam.elements,
               "elements_campbell": campbell.parameters.beam.elements}),
    );
    report.parameters.insert("cb_modes".into(), json!(modes));
    report
        .parameters
        .insert("rates_rad_s".into(), json!(spin.parameters.rates));
    report
        .parameters
        .insert("ramp_s".into(), json!(spin.parameters.ramp));
    report
        .parameters
        .insert("step_s".into(), json!(spin.parameters.integration.step));
    let campbell_table = campbell_report(&campbell, &mut report, modes);
    let spin_table = spin_report(&spin, &mut report);
    report.table = format!(
        "## Campbell diagram\n\nThe clamped-free beam spun about its root: flapwise and \
         lagwise frequencies μ = ω√(ρAL⁴/EI) against λ = Ω√(ρAL⁴/EI), beside the published \
         flapwise values (Wright, Smith, Thresher & Wang 1982; Hodges & Rutkowski 1981), \
         tolerance {PUBLISHED_TOLERANCE} for λ ≤ {COMPARED_UP_TO}.\n\n{campbell_table}\n\
         ## Kane's spin-up\n\nThe 10 m beam (EI = 14 000 N m², ρA = 1.2 kg/m, EA = 2.8e7 N) \
         on a hub turned by θ(t) = (ω_s/T_s)(t²/2 + (T_s/2π)²(cos 2πt/T_s − 1)), T_s = 15 s: \
         the tip's deflection in the hub frame against a co-rotational beam computed \
         independently (assets/generate/spinning_beam_reference.py), tolerance \
         {SPIN_UP_TOLERANCE} of its peak.\n\n{spin_table}",
        PUBLISHED_TOLERANCE = flexmodes_core::report::readable(PUBLISHED_TOLERANCE, 1),
        SPIN_UP_TOLERANCE = flexmodes_core::report::readable(SPIN_UP_TOLERANCE, 1)
    );
    let markdown = format!(
        "# spin-up\n\nA floating-frame body whose elastic coordinates enter linearly has no \
         dynamic (geometric) stiffening: spun, it keeps the centrifugal softening (H) but \
         loses the centrifugal tension, so its frequencies fall with the rate and above the \
         first bending frequency it diverges (Lin's thesis §1, refs. [16] Kane et al. 1987, \
         [18] Zhang & Huston 1996). flexmodes adds the geometric stiffness of each unit \
         inertia load of the frame (rate², angular acceleration, gravity), solved statically \
         once and projected on each model's basis. Views: the Campbell charts, flapwise and \
         lagwise (μ on decades against λ; the published values as grey points; the lighter \
         lines, `unstiff.` in the legend, without stiffening; μ₁ and μ₂ of a model share its \
         colour; a lagwise line ending where the model turns unstable); the \
         tip's deflection (m) over time at each ω_s by the stiffened models beside the \
         reference (`tip, m: 4`, `tip, m: 10`), and the unstiffened ones running off to the \
         beam's length (`unstiffened`).\n\n{}",
        report.table
    );
    let mut visuals = campbell_visuals(&campbell);
    visuals.extend(spin_visuals(&spin));
    let mut plots: Vec<Layout> = spin
        .parameters
        .rates
        .iter()
        .map(|r| Layout::TimeSeries {
            name: format!("tip, m: {r}"),
            origin: format!("/plots/tip_{}", rate_key(*r)),
        })
        .collect();
    plots.push(Layout::TimeSeries {
        name: "unstiffened".into(),
        origin: "/plots/unstiffened".into(),
    });
    plots.insert(
        0,
        Layout::Spatial2D {
            name: "lag".into(),
            origin: "/campbell/lagwise".into(),
        },
    );
    plots.insert(
        0,
        Layout::Spatial2D {
            name: "flap".into(),
            origin: "/campbell/flapwise".into(),
        },
    );
    let views = Layout::Tabs(plots);
    Ok(SceneOutput::beside_text(report, markdown, visuals, views)
        .on_timeline("sim_time")
        .y_up())
}

fn rate_key(rate: f64) -> String {
    format!("{rate}").replace('.', "_")
}

/// A model's name in a Campbell chart's legend, short enough for two to a row in the
/// smallest view (`CB 6 unstiff.`: without the dynamic stiffening).
fn legend_label(modes: usize, stiffening: bool) -> String {
    let model = crate::models::model_name(modes);
    if stiffening {
        model
    } else {
        format!("{model} unstiff.")
    }
}

fn model_color(modes: usize, stiffening: bool) -> Color {
    let method = if modes == 0 {
        Method::NoReduction
    } else {
        Method::CraigBampton
    };
    let c = method_color(method);
    if stiffening {
        c
    } else {
        // The unstiffened model in the method's colour, lighter.
        [c[0] / 2 + 110, c[1] / 2 + 60, c[2] / 2 + 40, 255]
    }
}

fn campbell_report(study: &CampbellStudy, report: &mut Report, modes: usize) -> String {
    let speeds = &study.parameters.speeds;
    let flap = |m, s| study.curve(m, s, BendingPlane::Flapwise).expect("computed");
    let lag = |m, s| study.curve(m, s, BendingPlane::Lagwise).expect("computed");
    let mut table = Table::new(&[
        "λ",
        "published μ₁",
        "NR μ₁",
        &format!("CB {modes} μ₁"),
        "published μ₂",
        "NR μ₂",
        &format!("CB {modes} μ₂"),
        "NR lag μ₁",
        "NR lag μ₁, no stiffening",
    ]);
    let num = |v: f64| Cell::number(v, format!("{v:.4}"));
    for (i, &l) in speeds.iter().enumerate() {
        let published = study.published.iter().find(|r| r[0] == l);
        let p = |k: usize| published.map_or(Cell::text("–"), |r| num(r[k]));
        let (nr, cb) = (flap(0, true).mu()[i], flap(modes, true).mu()[i]);
        let lag_on = lag(0, true).mu()[i][0];
        let lag_off = lag(0, false).mu_squared[i][0];
        let off = if lag_off <= 0.0 {
            Cell::number(0.0, format!("unstable (μ² = {lag_off:.2})"))
        } else {
            num(lag_off.sqrt())
        };
        table.push(vec![
            Cell::text(format!("{l}")),
            p(1),
            num(nr[0]),
            num(cb[0]),
            p(2),
            num(nr[1]),
            num(cb[1]),
            num(lag_on),
            off,
        ]);
    }
    let nr_diff = study.published_difference(flap(0, true), COMPARED_UP_TO);
    let cb_diff = study.published_difference(flap(modes, true), COMPARED_UP_TO);
    let off_diff = study.published_difference(flap(0, false), COMPARED_UP_TO);
    let unstable = lag(0, false).unstable_from(speeds);
    let mu1 = flap(0, true).mu()[0][0];
    let r = &mut report.results;
    r.insert(
        "campbell".into(),
        json!({
            "published_difference": {"nr": sig(nr_diff), "cb": sig(cb_diff),
                                     "nr_no_stiffening": sig(off_diff)},
            "flapwise_nr": study.curves.iter().find(|c| c.modes == 0 && c.stiffening
                && c.plane == BendingPlane::Flapwise).map(|c| c.mu().iter()
                .map(|p| [sig(p[0]), sig(p[1])]).collect::<Vec<_>>()),
            "lagwise_unstable_from_lambda_without_stiffening": unstable,
            "first_frequency_at_rest_mu": sig(mu1),
            "max_residual": study.max_residual,
        }),
    );
    format!(
        "{}\nLargest difference from the published flapwise values for λ ≤ {COMPARED_UP_TO}: \
         NR {nr_diff}, CB {modes} {cb_diff} (without stiffening: {off_diff}: the \
         frequency at rest at every speed). Without stiffening the lagwise frequency is \
         √(μ₁² − λ²): it reaches zero at λ = μ₁ = {mu1:.4} and the model is unstable from \
         λ = {} on. Largest relative eigenpair residual {}.\n",
        report.add_table(table),
        unstable.map_or("–".into(), |u| format!("{u}")),
        flexmodes_core::report::readable(study.max_residual, 1),
        nr_diff = flexmodes_core::report::readable(nr_diff, 2),
        cb_diff = flexmodes_core::report::readable(cb_diff, 2),
        off_diff = flexmodes_core::report::readable(off_diff, 2),
    )
}

fn spin_report(study: &SpinUpStudy, report: &mut Report) -> String {
    let mut table = Table::new(&[
        "ω_s, rad/s",
        "model",
        "peak tip deflection, m",
        "difference / reference peak",
        "online, s",
        "diverged",
    ]);
    let mut results = serde_json::Map::new();
    for run in &study.runs {
        let reference = spin_up_reference(run.rate).filter(|r| r.len() > 1);
        let diff = reference.as_ref().map(|r| run.difference(r));
        let diverged = run.divergence.map_or("no".to_string(), |d| {
            format!(
                "at t = {:.2} s, hub at {:.2} rad/s (passed ω₁ = {:.3} rad/s at t = {})",
                d.time,
                d.rate,
                study.first_frequency,
                d.rate_passed_first_frequency
                    .map_or("–".into(), |t| format!("{t:.2} s"))
            )
        });
        table.push(vec![
            Cell::text(format!("{}", run.rate)),
            Cell::text(run.label()),
            Cell::number(run.peak(), format!("{:.4}", run.peak())),
            diff.map_or(Cell::text("–"), |d| Cell::number(d, format!("{d:.3}"))),
            Cell::number(run.online_s, format!("{:.3}", run.online_s)),
            Cell::text(diverged),
        ]);
        results.insert(
            format!("{}/{}", rate_key(run.rate), run.label()),
            json!({"peak_m": sig(run.peak()), "difference": diff.map(sig),
                   "diverged_at_s": run.divergence.map(|d| sig(d.time))}),
        );
    }
    for rate in &study.parameters.rates {
        if let Some(r) = spin_up_reference(*rate).filter(|r| r.len() > 1) {
            let peak = r.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
            results.insert(
                format!("{}/reference", rate_key(*rate)),
                json!({"peak_m": sig(peak)}),
            );
        }
    }
    report
        .results
        .insert("spin_up".into(), serde_json::Value::Object(results));
    report.results.insert(
        "first_frequency_rad_s".into(),
        json!(sig(study.first_frequency)),
    );
    report.add_table(table)
}

/// The Campbell charts, flapwise and lagwise: μ against λ on a semi-log chart (λ linear, μ
/// on decades), one line per model and mode (the model named once in the legend), the
/// published flapwise values as points; a
/// model's pairs with μ² ≤ 0 (unstable) have no place on the log axis and end its line.
fn campbell_visuals(study: &CampbellStudy) -> Vec<Visual> {
    let speeds = &study.parameters.speeds;
    let mut visuals = Vec::new();
    for (plane, key) in [
        (BendingPlane::Flapwise, "flapwise"),
        (BendingPlane::Lagwise, "lagwise"),
    ] {
        let mut series = Vec::new();
        for curve in study.curves.iter().filter(|c| c.plane == plane) {
            let id = curve.label().replace([' ', ','], "_").to_lowercase();
            for m in 0..2 {
                let points: Vec<(f64, f64)> = speeds
                    .iter()
                    .zip(&curve.mu_squared)
                    .take_while(|(_, mu2)| mu2[m] > 0.0)
                    .map(|(&l, mu2)| (l, mu2[m].sqrt()))
                    .collect();
                // One legend entry per model: its two modes share its colour.
                series.push(LogLogSeries {
                    id: format!("{id}_mode{}", m + 1),
                    label: if m == 0 {
                        legend_label(curve.modes, curve.stiffening)
                    } else {
                        String::new()
                    },
                    color: model_color(curve.modes, curve.stiffening),
                    points,
                    line: true,
                });
            }
        }
        if plane == BendingPlane::Flapwise {
            series.push(LogLogSeries {
                id: "published".into(),
                label: "published".into(),
                color: REFERENCE,
                points: study
                    .published
                    .iter()
                    .flat_map(|r| [(r[0], r[1]), (r[0], r[2])])
                    .collect(),
                line: false,
            });
        }
        visuals.extend(
            LogLogChart {
                path: format!("campbell/{key}"),
                x_unit: "λ".into(),
                y_unit: "μ₁, μ₂".into(),
                series,
                x_linear: true,
            }
            .visuals(),
        );
    }
    visuals
}

fn spin_visuals(study: &SpinUpStudy) -> Vec<Visual> {
    let mut visuals = Vec::new();
    // The stiffened models beside the reference, one view per rate; the unstiffened ones,
    // which run off to the beam's length, in a view of their own so the others keep a scale
    // their difference shows on.
    for run in &study.runs {
        let key = run.label().replace([' ', ','], "_").to_lowercase();
        let (path, name) = if run.stiffening {
            (
                format!("plots/tip_{}/{key}", rate_key(run.rate)),
                run.label(),
            )
        } else {
            (
                format!("plots/unstiffened/{}_{key}", rate_key(run.rate)),
                format!("{}, ω_s {}", run.label(), run.rate),
            )
        };
        visuals.push(Visual::Series {
            path,
            times: run.times.clone(),
            values: run.tip.clone(),
            name,
            color: model_color(run.modes, run.stiffening),
        });
    }
    for rate in &study.parameters.rates {
        if let Some(r) = spin_up_reference(*rate).filter(|r| r.len() > 1) {
            visuals.push(Visual::Series {
                path: format!("plots/tip_{}/reference", rate_key(*rate)),
                times: r.iter().map(|p| p.0).collect(),
                values: r.iter().map(|p| p.1).collect(),
                name: "co-rotational reference".into(),
                color: REFERENCE,
            });
        }
    }
    visuals
}
