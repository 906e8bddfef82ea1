//! `beam-eitelberg`: Eitelberg's method on Guyan (a)'s masters (§6.6.4).

use crate::linalg::LinalgError;
use crate::record::method_color;
use crate::reduction::{ReductionRequest, reduce};
use serde_json::json;

use crate::scenes::{
    SceneInfo, SceneOptions, SceneOutput,
    mode_visuals::{columns, mode_set, undeformed},
};
use crate::{
    Result,
    analysis::{reduced_hz, reduced_modes},
    fem::{BeamParameters, FeModel, beam},
    linalg::principal_angles,
    record::{Layout, Visual},
    reduction::{Basis, EitelbergParameters, EitelbergReduction, Method, eitelberg},
    report::{Report, Table, fmt_hz, sig, sig_vec},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "beam-eitelberg",
    recording_cost: 0,
    summary: "§6.6 Eitelberg's method on the beam (masters 1, 3, 5) with the L = [I I] \
              output-feedback trick; the restored M^-1 K equals Guyan's",
    sections: "§6.6, App. C",
    controls: crate::scenes::scene_info::SceneControls {
        methods: &[Method::Eitelberg, Method::Guyan],
        boundary: &[1, 3, 5],
        ..crate::scenes::scene_info::SceneControls::NONE
    },
};

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    opts.methods_or(INFO.name, &[Method::Eitelberg, Method::Guyan], &[])?;
    let masters = opts.boundary_or_default(&INFO);
    let model = beam(&BeamParameters::default());
    let eit = eitelberg(&model, &masters, &EitelbergParameters::default())?;
    let g = reduce(
        &model,
        &ReductionRequest::of(Method::Guyan).boundary(&masters),
    )?;
    let guyan_hz = reduced_hz(&model, &g)?;
    let k_g = g.reduced_stiffness(&model);
    let m_g = g.reduced_mass(&model);
    let guyan_minv_k = m_g
        .llt(faer::Side::Lower)
        .map_err(|_| LinalgError::NotPositiveDefinite {
            matrix: "Guyan mass".into(),
        })?
        .solve(&k_g);
    use faer::prelude::Solve;
    let scale = crate::linalg::max_abs(guyan_minv_k.as_ref());
    let diff = crate::linalg::max_abs_diff(eit.minv_k.as_ref(), guyan_minv_k.as_ref()) / scale;
    let angles = principal_angles(eit.basis.psi.as_ref(), g.psi.as_ref())?;
    let max_angle = angles.iter().copied().fold(0.0f64, f64::max);

    let rows: Vec<Vec<f64>> = (0..eit.minv_k.nrows())
        .map(|i| {
            (0..eit.minv_k.ncols())
                .map(|j| sig(eit.minv_k[(i, j)]))
                .collect()
        })
        .collect();
    let mut report = Report::new(INFO.name);
    report.parameters.insert("boundary".into(), json!(masters));
    report
        .parameters
        .insert("output_feedback".into(), json!("L = [I I]"));
    let r = &mut report.results;
    r.insert("minv_k".into(), json!(rows));
    r.insert("hz".into(), json!(sig_vec(&eit.hz)));
    r.insert("guyan_hz".into(), json!(sig_vec(&guyan_hz)));
    r.insert("minv_k_rel_diff_vs_guyan".into(), json!(diff));
    r.insert("principal_angle_vs_guyan_max_rad".into(), json!(max_angle));
    r.insert(
        "gramian_condition".into(),
        json!(sig(eit.gramian_condition)),
    );
    r.insert(
        "zero_singular_values".into(),
        json!({"a": eit.zero_singular_values.0, "a_r_restored": eit.zero_singular_values.1}),
    );
    let matrix = matrix_text(&rows, scale);
    let hz_table = report.add_table(Table::from_text(
        &["", "Hz"],
        &[
            vec!["Eitelberg".into(), fmt_hz(&eit.hz)],
            vec!["Guyan".into(), fmt_hz(&guyan_hz)],
            vec![
                "published (§6.6.4)".into(),
                "5.95823, 71.1763, 123.281".into(),
            ],
        ],
    ));
    report.table = format!(
        "Restored M⁻¹K (1/s², rows/columns: boundary DOF of nodes {masters:?}):\n\n{matrix}\n\
         {hz_table}\n\
         Largest relative difference to Guyan's M⁻¹K: {} (R S R^T has condition number \
         {}, so about five digits are lost to round-off); largest principal angle between \
         the implied basis and Ψ_Guyan: {} rad; zero singular values of A / restored A_r: \
         {} / {}.\n",
        flexmodes_core::report::readable(diff, 2),
        flexmodes_core::report::readable(eit.gramian_condition, 2),
        flexmodes_core::report::readable(max_angle, 2),
        eit.zero_singular_values.0,
        eit.zero_singular_values.1,
    );
    let markdown = scene_text(&masters, &report.table);
    let (visuals, views) = mode_views(&model, &eit, &g)?;
    Ok(SceneOutput::beside_text(report, markdown, visuals, views)
        .on_timeline("phase")
        .y_up())
}

/// The restored $M^{-1}K$ as a fixed-width block, round-off below 1e-9 of `scale` shown as 0.
fn matrix_text(rows: &[Vec<f64>], scale: f64) -> String {
    let mut matrix = String::from("```\n");
    for row in rows {
        matrix.push_str(
            &row.iter()
                .map(|&v| format!("{:>12}", tidy(v, scale)))
                .collect::<Vec<_>>()
                .join(" "),
        );
        matrix.push('\n');
    }
    matrix.push_str("```\n");
    matrix
}

/// The scene's text above its `table`.
fn scene_text(masters: &[usize], table: &str) -> String {
    format!(
        "# beam-eitelberg\n\nEitelberg's reduction (App. C) of the beam in state-space form \
         x = [δ; δ̇], keeping δ_b and δ̇_b of nodes {masters:?}. The undamped A is singular and \
         not asymptotically stable, so A − B L C with L = [I I] (unit springs and dampers at \
         the boundary) is reduced and A_r + B_r L C_r restored afterwards. The restored M⁻¹K and \
         its frequencies equal Guyan reduction's: for structures Eitelberg's method *is* Guyan \
         reduction (§6.6.4). The views animate the reduced model's modes expanded by the implied \
         basis S R^T(R S R^T)⁻¹ beside Guyan (a)'s.\n\n{}",
        table
    )
}

/// The reduced model's modes expanded by Eitelberg's implied basis, beside Guyan (a)'s.
fn mode_views(
    model: &FeModel,
    eit: &EitelbergReduction,
    g: &Basis,
) -> Result<(Vec<Visual>, Layout)> {
    let guyan_modes = {
        let e = reduced_modes(model, g)?;
        let full = &g.psi * &e.vectors;
        columns(&full)
            .into_iter()
            .zip(e.hz())
            .skip(e.zero_energy)
            .enumerate()
            .map(|(k, (u, f))| (u, format!("Guyan {}: {f:.6} Hz", k + 1)))
            .collect::<Vec<_>>()
    };
    let eit_modes = eitelberg_modes(eit)?;
    let mut visuals = vec![undeformed(model)];
    visuals.extend(mode_set(
        model,
        "eitelberg",
        &eit_modes,
        method_color(Method::Eitelberg),
    ));
    visuals.extend(mode_set(
        model,
        "guyan_a",
        &guyan_modes,
        method_color(Method::Guyan),
    ));
    let views = Layout::Vertical(
        vec![
            Layout::view3d("eitelberg", "/modes/eitelberg"),
            Layout::view3d("guyan_a", "/modes/guyan_a"),
        ],
        vec![1.0, 1.0],
    );
    Ok((visuals, views))
}

/// A matrix entry as the thesis prints it (5 significant digits), with round-off below
/// 1e-9 of the matrix's largest entry shown as 0.
fn tidy(v: f64, scale: f64) -> String {
    if v.abs() <= 1e-9 * scale {
        "0".into()
    } else {
        format!("{}", crate::report::sig5(v))
    }
}

/// Elastic modes of the restored $\underline M^{-1}\underline K$ (real parts of its
/// eigenvectors; its eigenvalues are real), expanded to the full DOF by the implied basis.
fn eitelberg_modes(eit: &EitelbergReduction) -> Result<Vec<(Vec<f64>, String)>> {
    let evd = eit
        .minv_k
        .eigen()
        .map_err(|_| LinalgError::DecompositionFailed {
            what: "restored M^-1 K eigen".into(),
        })?;
    let nb = eit.minv_k.nrows();
    // Zero energy against the restored matrix' own scale, as for the symmetric solves.
    let scale = (0..nb).fold(0.0f64, |a, j| a.max(evd.S()[j].re.abs()));
    let mut modes: Vec<(f64, Vec<f64>)> = (0..nb)
        .filter(|&j| evd.S()[j].re.abs() > crate::linalg::ZERO_ENERGY_RATIO * scale)
        .map(|j| {
            let hz = crate::linalg::hz_from_eigenvalue(evd.S()[j].re);
            let v = faer::Mat::from_fn(nb, 1, |i, _| evd.U()[(i, j)].re);
            let u = &eit.basis.psi * &v;
            (hz, (0..u.nrows()).map(|i| u[(i, 0)]).collect())
        })
        .collect();
    modes.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(modes
        .into_iter()
        .enumerate()
        .map(|(k, (hz, u))| (u, format!("Eitelberg {}: {hz:.6} Hz", k + 1)))
        .collect())
}
