//! The body modes scene's report: the rows of every method, the interface-reduction sweep and the run's parameters.

use crate::models::MethodMeasure;
use crate::record::{LogLogChart, LogLogSeries};
use crate::scenes::{SceneOptions, frequency_bars::FrequencyBars};
use crate::{
    body_file::ImportedBody,
    record::Layout,
    reduction::Method,
    report::{Cell, Table, fmt_hz, residual_note, sig, sig_vec},
};
use serde_json::{Map, Value, json};

/// The interface-reduction sweep as the `modes` scene shows it.
pub(super) struct SweepSection {
    pub(super) table: Table,
    pub(super) json: Value,
    pub(super) visuals: Vec<crate::record::Visual>,
    pub(super) view: Layout,
    pub(super) markdown: String,
}

/// The sweep's table, JSON, log–log chart and text; `interface_modes` is the count the
/// scene's models use, if any.
pub(super) fn sweep_section(
    points: &[crate::models::InterfaceReductionPoint],
    interface_modes: Option<usize>,
) -> SweepSection {
    let mut sweep = Table::new(&["interface shapes", "size", "max rel. error, first 6 modes"]);
    let mut chart = Vec::new();
    for p in points {
        let shapes = p
            .interface_modes
            .map_or("all (plain CB)".to_string(), |n| n.to_string());
        sweep.push(vec![
            Cell::text(shapes),
            Cell::number(p.size as f64, format!("{}", p.size)),
            Cell::number(p.worst_error, crate::report::sig3(p.worst_error)),
        ]);
        if p.worst_error.is_finite() && p.worst_error > 0.0 {
            chart.push((p.size as f64, p.worst_error));
        }
    }
    let json = json!(
        points
            .iter()
            .map(|p| json!({
                "interface_modes": p.interface_modes,
                "size": p.size,
                "max_rel_error": sig(p.worst_error),
            }))
            .collect::<Vec<_>>()
    );
    let visuals = LogLogChart {
        path: "charts/interface_reduction".into(),
        x_unit: "coordinates".into(),
        y_unit: "max rel. error".into(),
        series: vec![LogLogSeries {
            id: "cb".into(),
            label: "CB, N characteristic constraint modes".into(),
            color: crate::record::method_color(Method::CraigBampton),
            points: chart,
            line: true,
        }],
        x_linear: false,
    }
    .visuals();
    let view = Layout::Spatial2D {
        name: "interface shapes: error against size".into(),
        origin: "/charts/interface_reduction".into(),
    };
    let markdown = format!(
        "\nInterface reduction (Craig–Bampton with the interface's constraint modes \
         replaced by N characteristic constraint modes, Castanier–Tan–Pierre; \
         `--interface-modes N`{}):\n\n{}",
        match interface_modes {
            Some(n) => format!(
                "; the models above use N = {n} where they have constraint modes (GR, CB), \
                 MT and MC keep their boundary columns"
            ),
            None => String::new(),
        },
        sweep.markdown()
    );
    SweepSection {
        table: sweep,
        json,
        visuals,
        view,
        markdown,
    }
}

/// The run's parameters as the report shows them: the body, its interface (plain, rbe2 and
/// rbe3 items), the kept modes and the methods.
pub(super) fn run_parameters(
    body: &ImportedBody,
    boundary: &[usize],
    opts: &SceneOptions,
    kept: usize,
    methods: &[Method],
) -> Map<String, Value> {
    let mut p = Map::new();
    p.insert("body".into(), json!(body.location.display()));
    p.insert("boundary".into(), json!(boundary));
    p.insert(
        "rigid_interfaces".into(),
        json!(
            opts.rigid_interfaces
                .iter()
                .map(|i| json!({"name": i.name, "kind": "rbe2", "master": i.master, "nodes": i.nodes.len()}))
                .collect::<Vec<_>>()
        ),
    );
    p.insert(
        "averaging_interfaces".into(),
        json!(
            opts.averaging_interfaces
                .iter()
                .map(|i| json!({"name": i.name, "kind": "rbe3", "master": i.master, "nodes": i.nodes.len()}))
                .collect::<Vec<_>>()
        ),
    );
    p.insert("modes".into(), json!(kept));
    p.insert(
        "methods".into(),
        json!(methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
    );
    p
}

/// The per-method part of the `modes` scene's report: its table rows, JSON maps, residual
/// lines, notes and responses; each model's frequencies added to `freq_bars`.
pub(super) struct MethodRows {
    pub(super) table: Table,
    pub(super) reduced: Map<String, Value>,
    pub(super) errors: Map<String, Value>,
    pub(super) angles: Map<String, Value>,
    pub(super) mac: Map<String, Value>,
    pub(super) rigid_max: Map<String, Value>,
    pub(super) reduced_residuals: Map<String, Value>,
    pub(super) reduced_zero: Map<String, Value>,
    pub(super) sizes: Map<String, Value>,
    pub(super) residual_lines: Vec<String>,
    pub(super) notes: Vec<String>,
    pub(super) responses: Vec<(Method, crate::analysis::FrequencyResponse)>,
}

impl MethodRows {
    /// The body's size and the frequencies, residuals and zero-energy modes of the full body,
    /// the fixed interface and every method, moved into the report's results.
    pub(super) fn insert_frequencies(
        &mut self,
        r: &mut Map<String, Value>,
        full: &crate::analysis::ZeroEnergyCount,
        (full_hz, fi_hz): (&[f64], &[f64]),
        fi_residuals: &[f64],
        model: &crate::fem::FeModel,
    ) {
        r.insert("dofs".into(), json!(model.dof_count()));
        r.insert("nnz".into(), json!(model.stiffness_nnz()));
        r.insert("zero_energy_modes".into(), json!(full.zero_modes));
        r.insert(
            "missed_modes".into(),
            json!(full.modes.sturm.map_or(0, |c| c.missed())),
        );
        r.insert("free_free_hz".into(), json!(sig_vec(full_hz)));
        r.insert("fixed_interface_hz".into(), json!(sig_vec(fi_hz)));
        r.insert(
            "reduced_hz".into(),
            Value::Object(std::mem::take(&mut self.reduced)),
        );
        r.insert(
            "free_free_residuals".into(),
            json!(sig_vec(&full.elastic_residuals())),
        );
        r.insert(
            "fixed_interface_residuals".into(),
            json!(sig_vec(fi_residuals)),
        );
        r.insert(
            "reduced_residuals".into(),
            Value::Object(std::mem::take(&mut self.reduced_residuals)),
        );
        r.insert(
            "reduced_zero_energy_modes".into(),
            Value::Object(std::mem::take(&mut self.reduced_zero)),
        );
    }

    /// Every method's errors, angles, MAC, size and rigid-mode frequencies, the full body's
    /// solve time (s) and the notes, moved into the report's results.
    pub(super) fn insert_measures(&mut self, r: &mut Map<String, Value>, full_s: f64) {
        r.insert(
            "rel_error".into(),
            Value::Object(std::mem::take(&mut self.errors)),
        );
        r.insert(
            "max_principal_angle_rad".into(),
            Value::Object(std::mem::take(&mut self.angles)),
        );
        r.insert("mac".into(), Value::Object(std::mem::take(&mut self.mac)));
        r.insert(
            "basis_size".into(),
            Value::Object(std::mem::take(&mut self.sizes)),
        );
        r.insert(
            "zero_energy_hz_max".into(),
            Value::Object(std::mem::take(&mut self.rigid_max)),
        );
        r.insert("full_modes_s".into(), json!(sig(full_s)));
        r.insert("method_notes".into(), json!(self.notes));
    }
}

pub(super) fn method_rows(
    methods: &[(Method, std::result::Result<MethodMeasure, String>)],
    model_notes: &[(Method, String)],
    dofs: usize,
    freq_bars: &mut FrequencyBars,
) -> MethodRows {
    let mut reduced = Map::new();
    let mut errors = Map::new();
    let mut angles = Map::new();
    let mut mac = Map::new();
    let mut rigid_max = Map::new();
    let mut reduced_residuals = Map::new();
    let mut reduced_zero = Map::new();
    let mut sizes = Map::new();
    let mut residual_lines = Vec::new();
    let mut table = Table::new(&[
        "model",
        "size",
        "lowest elastic Hz",
        "max rel. error, first 6 modes",
        "min MAC, first 6 modes",
        "largest angle to full modes (rad)",
        "rigid modes at ≤ Hz",
        "s",
    ])
    .rank_lower(&[3, 5, 6]);
    let mut notes = Vec::new();
    let mut responses = Vec::new();
    for (m, measured) in methods {
        let m = *m;
        let q = match measured {
            Ok(q) => q,
            Err(e) => {
                let mut row = vec![Cell::text(m.id().to_uppercase()), Cell::text("–")];
                row.push(Cell::text(format!("not computed: {e}")));
                row.extend((0..5).map(|_| Cell::text("–")));
                table.push(row);
                notes.push(format!("{}: {e}", m.id().to_uppercase()));
                continue;
            }
        };
        if let Some((_, note)) = model_notes.iter().find(|(n, _)| *n == m) {
            notes.push(format!("{}: {note}", m.id().to_uppercase()));
        }
        if let Some(r) = &q.response {
            responses.push((m, r.clone()));
        }
        let (hz, hz_residuals) = (&q.hz, &q.residuals);
        mac.insert(m.id().into(), json!(sig_vec(&q.macs)));
        reduced.insert(m.id().into(), json!(sig_vec(hz)));
        reduced_residuals.insert(m.id().into(), json!(sig_vec(hz_residuals)));
        reduced_zero.insert(m.id().into(), json!(q.zero_modes));
        residual_lines.push(format!(
            "{}: {}",
            m.id().to_uppercase(),
            residual_note(hz, hz_residuals)
        ));
        errors.insert(m.id().into(), json!(sig_vec(&q.rel_errors)));
        angles.insert(m.id().into(), json!(sig(q.max_angle)));
        rigid_max.insert(m.id().into(), json!(sig(q.rigid_hz_max)));
        sizes.insert(m.id().into(), json!(q.size));
        let (worst, min_mac, angle, rigid_hz) =
            (q.worst_error, q.min_mac, q.max_angle, q.rigid_hz_max);
        table.push(vec![
            Cell::text(m.id().to_uppercase()),
            Cell::number(q.size as f64, format!("{dofs} × {}", q.size)),
            Cell::text(fmt_hz(&hz[..hz.len().min(5)])),
            if worst.is_nan() {
                Cell::text(format!("{} elastic mode(s) only", hz.len()))
            } else {
                Cell::number(worst, crate::report::sig3(worst))
            },
            if min_mac.is_nan() {
                Cell::text("–")
            } else {
                Cell::number(min_mac, format!("{min_mac:.4}"))
            },
            Cell::number(angle, crate::report::sig3(angle)),
            Cell::number(rigid_hz, crate::report::sig3(rigid_hz)),
            Cell::number(q.offline_s, format!("{:.3}", q.offline_s)),
        ]);
        freq_bars.push(m, hz);
    }
    MethodRows {
        table,
        reduced,
        errors,
        angles,
        mac,
        rigid_max,
        reduced_residuals,
        reduced_zero,
        sizes,
        residual_lines,
        notes,
        responses,
    }
}
