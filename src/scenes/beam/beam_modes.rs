//! `beam-modes`: the App. A beam's mode sets of chapter 6 (Figs. 6-1 to 6-9).

use crate::record::{REFERENCE, method_color};
use crate::reduction::{ReductionRequest, reduce};
use serde_json::json;

use super::beam_run::BeamRun;
use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    mode_visuals::{columns, mode_set, undeformed},
};
use crate::{
    Result,
    analysis::{elastic_hz, free_free_modes, reduced_hz, reduced_modes},
    fem::FeModel,
    linalg::{GeneralizedEigen, principal_angles},
    record::{Layout, Visual},
    reduction::{Basis, Method, ModeSelection, Partition, fixed_interface_modes},
    report::{Table, fmt_hz, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "beam-modes",
    recording_cost: 0,
    summary: "App. A beam: free-free, Guyan (a)(b)(c), boundary, fixed-interface, Craig-Bampton \
              and mode-condensation mode shapes (Figs. 6-1 to 6-9)",
    sections: "§6.2-6.5, App. A",
    controls: super::beam_run::beam_controls(&[
        Method::Guyan,
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ]),
};

const MASTERS_A: [usize; 3] = [1, 3, 5];
const MASTERS_B: [usize; 3] = [1, 2, 5];
const AVAILABLE: [Method; 4] = [
    Method::Guyan,
    Method::ModalTruncation,
    Method::CraigBampton,
    Method::ModeCondensation,
];

/// Elastic modes of a reduced model, expanded to the full DOF: $\delta = \Psi v$.
fn expanded_modes(model: &FeModel, basis: &Basis, prefix: &str) -> Result<Vec<(Vec<f64>, String)>> {
    let e = reduced_modes(model, basis)?;
    let hz = e.hz();
    let full = &basis.psi * &e.vectors;
    Ok(columns(&full)
        .into_iter()
        .zip(hz)
        .skip(e.zero_energy)
        .enumerate()
        .map(|(k, (u, f))| (u, format!("{prefix} {}: {f:.6} Hz", k + 1)))
        .collect())
}

fn labelled_columns(basis: &Basis) -> Vec<(Vec<f64>, String)> {
    columns(&basis.psi)
        .into_iter()
        .zip(&basis.columns)
        .map(|(u, c)| (u, c.label.clone()))
        .collect()
}

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let run = BeamRun::new(opts, &INFO, (&AVAILABLE, &AVAILABLE))?;
    let mut report = run.report(&INFO);
    let (methods, boundary, kept, model, part) = run.into_parts();

    let ff = free_free_modes(&model)?;
    let free_free_hz = elastic_hz(&ff);
    let guyan = |masters: &[usize]| {
        reduce(
            &model,
            &ReductionRequest::of(Method::Guyan).boundary(masters),
        )
    };
    let (g_a, g_b, g_c) = (guyan(&MASTERS_A)?, guyan(&MASTERS_B)?, guyan(&boundary)?);
    let fi = fixed_interface_modes(&model, &part)?;
    let fixed_interface_hz = fi.hz();
    let request = ReductionRequest::default()
        .boundary(&boundary)
        .modes(ModeSelection::Count(kept));
    let [mt, cb, mc] = [
        Method::ModalTruncation,
        Method::CraigBampton,
        Method::ModeCondensation,
    ]
    .map(|m| reduce(&model, &request.with_method(m)));
    let (mt, cb, mc) = (mt?, cb?, mc?);
    let angles = principal_angles(cb.psi.as_ref(), mc.psi.as_ref())?;
    let max_angle = angles.iter().copied().fold(0.0f64, f64::max);

    let guyan_a_hz = reduced_hz(&model, &g_a)?;
    let guyan_b_hz = reduced_hz(&model, &g_b)?;
    let guyan_c_hz = reduced_hz(&model, &g_c)?;
    let cb_hz = reduced_hz(&model, &cb)?;
    let mc_hz = reduced_hz(&model, &mc)?;

    let r = &mut report.results;
    for (key, hz) in [
        ("free_free_hz", &free_free_hz),
        ("guyan_a_hz", &guyan_a_hz),
        ("guyan_b_hz", &guyan_b_hz),
        ("guyan_c_hz", &guyan_c_hz),
        ("fixed_interface_hz", &fixed_interface_hz),
        ("cb_hz", &cb_hz),
        ("mc_hz", &mc_hz),
    ] {
        r.insert(key.into(), json!(sig_vec(hz)));
    }
    r.insert("principal_angle_cb_mc_max_rad".into(), json!(max_angle));

    let b = format!("{boundary:?}");
    let rows = mode_set_rows(
        &b,
        kept,
        [
            &free_free_hz,
            &guyan_a_hz,
            &guyan_b_hz,
            &guyan_c_hz,
            &fixed_interface_hz,
            &cb_hz,
            &mc_hz,
        ],
    );
    report.table = format!(
        "{}\nLargest principal angle between span(Ψ_CB) and span(Ψ_MC): {} rad (§6.5.4: they \
         span one space).\n",
        report.add_table(Table::from_text(
            &["mode set", "computed, Hz", "published, Hz"],
            &rows
        )),
        flexmodes_core::report::readable(sig(max_angle), 3)
    );

    let markdown = scene_text(&b, kept, &report.table);

    let sets = BeamModeSets {
        ff: &ff,
        guyan: [&g_a, &g_b, &g_c],
        mt: &mt,
        fi: &fi,
        cb: &cb,
        mc: &mc,
    };
    let (visuals, views) = mode_set_views(&model, &part, &methods, &sets)?;
    Ok(SceneOutput::beside_text(report, markdown, visuals, views)
        .on_timeline("phase")
        .y_up())
}

/// The beam's mode sets as the scene draws them: the free-free modes, Guyan's three bases
/// (masters A, B and the boundary), the modal truncation basis with the fixed-interface modes,
/// and the Craig–Bampton and mode-condensation bases.
struct BeamModeSets<'a> {
    ff: &'a GeneralizedEigen,
    guyan: [&'a Basis; 3],
    mt: &'a Basis,
    fi: &'a GeneralizedEigen,
    cb: &'a Basis,
    mc: &'a Basis,
}

/// Each mode set of the `methods` drawn under `modes/<set>`, one tab each in two rows.
fn mode_set_views(
    model: &FeModel,
    part: &Partition,
    methods: &[Method],
    sets: &BeamModeSets<'_>,
) -> Result<(Vec<Visual>, Layout)> {
    let BeamModeSets {
        ff,
        guyan: [g_a, g_b, g_c],
        mt,
        fi,
        cb,
        mc,
    } = *sets;
    let mut visuals = vec![undeformed(model)];
    let mut tabs = Vec::new();
    let mut add = |set: &str, modes: Vec<(Vec<f64>, String)>, color, visuals: &mut Vec<Visual>| {
        visuals.extend(mode_set(model, set, &modes, color));
        tabs.push(Layout::view3d(tab_title(set), &format!("/modes/{set}")));
    };
    let ff_modes: Vec<(Vec<f64>, String)> = columns(&ff.vectors)
        .into_iter()
        .zip(ff.hz())
        .skip(ff.zero_energy)
        .enumerate()
        .map(|(k, (u, f))| (u, format!("free-free {}: {f:.6} Hz", k + 1)))
        .collect();
    add("free_free", ff_modes, REFERENCE, &mut visuals);
    if methods.contains(&Method::Guyan) {
        let c = method_color(Method::Guyan);
        for (set, basis, name) in [("guyan_a", g_a, "Guyan (a)"), ("guyan_b", g_b, "Guyan (b)")] {
            add(set, expanded_modes(model, basis, name)?, c, &mut visuals);
        }
        add("guyan_c", labelled_columns(g_c), c, &mut visuals);
    }
    if methods.contains(&Method::ModalTruncation) {
        let c = method_color(Method::ModalTruncation);
        let bcols: Vec<_> = labelled_columns(mt)
            .into_iter()
            .take(part.b.len())
            .collect();
        add("boundary", bcols, c, &mut visuals);
        let fi_modes: Vec<_> = columns(&part.assemble(
            faer::Mat::<f64>::zeros(part.b.len(), fi.vectors.ncols()).as_ref(),
            fi.vectors.as_ref(),
        ))
        .into_iter()
        .zip(fi.hz())
        .enumerate()
        .map(|(k, (u, f))| (u, format!("fixed-interface {}: {f:.6} Hz", k + 1)))
        .collect();
        add("fixed_interface", fi_modes, c, &mut visuals);
    }
    for (m, set, basis) in [
        (Method::CraigBampton, "craig_bampton", cb),
        (Method::ModeCondensation, "mode_condensation", mc),
    ] {
        if methods.contains(&m) {
            add(set, labelled_columns(basis), method_color(m), &mut visuals);
        }
    }
    // Two rows of tabs: the free-free and Guyan sets above, the rest below (eight tabs in one
    // row do not fit a 1280 × 800 window).
    let below = tabs.split_off(tabs.len().min(4));
    Ok((visuals, Layout::tab_rows(vec![tabs, below])))
}

/// A mode set's tab title, short enough for four tabs in a row of a 1280 × 800 window (the
/// scene text names the sets in full).
fn tab_title(set: &str) -> &str {
    match set {
        "fixed_interface" => "fixed",
        "craig_bampton" => "CB",
        "mode_condensation" => "MC",
        other => other,
    }
}

/// The mode sets' table rows against the published values: free-free, Guyan (a), (b), (c),
/// fixed-interface, Craig–Bampton and mode condensation, Hz; `b` is the boundary as written.
fn mode_set_rows(
    b: &str,
    kept: usize,
    [ff, ga, gb, gc, fi, cb, mc]: [&[f64]; 7],
) -> Vec<Vec<String>> {
    vec![
        vec![
            "free-free (Fig. 6-1)".into(),
            fmt_hz(ff),
            "5.94776, 66.7191, 123.281 (bending 1, axial 1, 2)".into(),
        ],
        vec![
            "Guyan (a), masters 1, 3, 5".into(),
            fmt_hz(ga),
            "5.95823, 71.1763, 123.281".into(),
        ],
        vec![
            "Guyan (b), masters 1, 2, 5".into(),
            fmt_hz(gb),
            "6.33897, 69.5245, ...".into(),
        ],
        vec![format!("Guyan (c), masters {b}"), fmt_hz(gc), "-".into()],
        vec![
            format!("fixed-interface, interface {b}"),
            fmt_hz(fi),
            "3.10366, 12.3283, ... (§8.5.2, nodes 1, 5)".into(),
        ],
        vec![
            format!("Craig-Bampton, {kept} modes"),
            fmt_hz(cb),
            "-".into(),
        ],
        vec![
            format!("mode condensation, {kept} modes"),
            fmt_hz(mc),
            "-".into(),
        ],
    ]
}

/// The scene's text around its `table`; `b` is the boundary as written.
fn scene_text(b: &str, kept: usize, table: &str) -> String {
    format!(
        "# beam-modes\n\nThe App. A beam (1 m, E = 30e5 Pa, I = 1.0417e-6 m⁴, A = 0.005 m², \
         four Euler-Bernoulli elements, rotations Guyan-condensed, lumped masses 0.1, 0.2, 0.2, \
         0.2, 0.1 kg) and the mode sets of chapter 6. Each view animates one set over the \
         `phase` timeline (one period in 32 steps); labels carry frequencies.\n\n\
         * **free_free**: the seven elastic free-free modes (Fig. 6-1).\n\
         * **guyan_a / guyan_b**: free-free modes of the Guyan models with masters 1, 3, 5 and \
         1, 2, 5 (Fig. 6-3): Guyan raises frequencies, and the lopsided masters of (b) break the \
         axial symmetry.\n\
         * **guyan_c**: constraint modes for masters {b} (Fig. 6-5).\n\
         * **boundary / fixed_interface** (tab \"fixed\"): modal truncation's boundary movements (no interior \
         motion, Fig. 6-6) and the fixed-interface normal modes (Fig. 6-7).\n\
         * **craig_bampton / mode_condensation** (tabs \"CB\", \"MC\"): Ψ_CB and Ψ_MC with {kept} kept modes \
         (Figs. 6-8, 6-9); different columns, one column space.\n\n{}",
        table
    )
}
