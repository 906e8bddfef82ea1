//! The mode views of a solid body: free-free, constraint and fixed-interface modes in tabs
//! above the reduced-frequency bar charts (the slab's, a refined slab's, an imported body's).

use faer::Mat;

use crate::record::method_color;
use crate::scenes::mode_visuals::{columns, mode_set};
use crate::{
    fem::FeModel,
    linalg::GeneralizedEigen,
    record::{Layout, Visual},
    reduction::{Method, Partition},
};

/// Constraint modes drawn at most (callers solve for these alone).
pub const MAX_DRAWN_CONSTRAINT_MODES: usize = 24;

/// What [`slab_mode_views`] draws: the body and its partition, its constraint modes
/// $[I; \Psi_s]$ of the boundary DOF with their labels, its fixed-interface and free-free
/// modes, and how many of each are shown.
pub struct ModeViews<'a> {
    pub model: &'a FeModel,
    pub part: &'a Partition,
    pub constraint: &'a Mat<f64>,
    pub constraint_labels: &'a [String],
    pub fixed_interface: &'a GeneralizedEigen,
    pub free_free: &'a GeneralizedEigen,
    /// Elastic free-free modes shown at most.
    pub shown_free_free: usize,
    /// Fixed-interface modes shown (the kept ones).
    pub kept: usize,
    /// The tab in front (`free_free`, `fixed_interface`).
    pub first_tab: &'a str,
    /// The charts below the tabs (the reduced-frequency chart first).
    pub charts: Vec<Layout>,
}

/// The slab's mode views: free-free elastic modes (at most `shown_free_free`), the constraint
/// modes and the first `kept` fixed-interface modes, each set under `modes/<set>/<k>`, and the
/// layout with those tabs (`first_tab` in front) above the `charts`, beside the scene text.
pub fn slab_mode_views(views: ModeViews<'_>) -> (Vec<Visual>, Layout) {
    let ModeViews {
        model,
        part,
        constraint,
        constraint_labels,
        fixed_interface,
        free_free,
        shown_free_free,
        kept,
        first_tab,
        charts,
    } = views;
    let mut visuals = Vec::new();
    let ff_modes: Vec<(Vec<f64>, String)> = columns(&free_free.vectors)
        .into_iter()
        .zip(free_free.hz())
        .skip(free_free.zero_energy)
        .take(shown_free_free)
        .enumerate()
        .map(|(k, (u, f))| (u, format!("{}: {f:.3} Hz", k + 1)))
        .collect();
    // The full body's own modes, in the full model's colour.
    visuals.extend(mode_set(
        model,
        "free_free",
        &ff_modes,
        method_color(Method::NoReduction),
    ));
    let nb = part.b.len();
    let coordinates = constraint_labels.len();
    // Bodies with large interfaces (an imported body's bolt hole) show the first few.
    let c_modes: Vec<(Vec<f64>, String)> = columns(constraint)
        .into_iter()
        .take(MAX_DRAWN_CONSTRAINT_MODES)
        .zip(constraint_labels)
        .map(|(u, label)| (u, label.clone()))
        .collect();
    visuals.extend(mode_set(
        model,
        "guyan_c",
        &c_modes,
        method_color(Method::Guyan),
    ));
    let shown = kept.min(fixed_interface.vectors.ncols());
    let fi_full = part.assemble(
        Mat::<f64>::zeros(nb, shown).as_ref(),
        fixed_interface.vectors.subcols(0, shown),
    );
    let fi_modes: Vec<(Vec<f64>, String)> = columns(&fi_full)
        .into_iter()
        .zip(fixed_interface.hz())
        .enumerate()
        .map(|(k, (u, f))| (u, format!("{}: {f:.3} Hz", k + 1)))
        .collect();
    visuals.extend(mode_set(
        model,
        "fixed_interface",
        &fi_modes,
        method_color(Method::CraigBampton),
    ));
    // A view that shows a subset says so in its tab.
    let constraint_tab = if coordinates > c_modes.len() {
        format!("guyan_c ({} of {coordinates})", c_modes.len())
    } else {
        "guyan_c".to_string()
    };
    let mut tabs: Vec<Layout> = [
        ("free_free", "free_free".to_string()),
        ("guyan_c", constraint_tab),
        ("fixed_interface", "fixed_interface".to_string()),
    ]
    .into_iter()
    .map(|(set, name)| Layout::view3d(&name, &format!("/modes/{set}")))
    .collect();
    if let Some(i) = ["free_free", "guyan_c", "fixed_interface"]
        .iter()
        .position(|s| *s == first_tab)
    {
        let front = tabs.remove(i);
        tabs.insert(0, front);
    }
    // The charts (the grouped frequency chart, and an imported body's interface sweep and
    // response where asked for) in one row under the modes, four ninths of the height: the
    // frequency chart's legend of nine models (NR and eight methods) needs ~230 pixels, and
    // at a third of 800 its last two entries were cut.
    let layout = Layout::beside_text(Layout::Vertical(
        vec![Layout::Tabs(tabs), Layout::Horizontal(charts, vec![])],
        vec![5.0, 4.0],
    ));
    (visuals, layout)
}
