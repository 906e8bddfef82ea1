//! `amls`: the last rung of the component-mode-synthesis ladder. A refined App. B slab cut by
//! nested dissection into a tree of parts and separators (drawn level by level); Guyan and
//! Craig–Bampton on the tree's root separator against multi-level substructuring (AMLS), in
//! which every part and separator keeps only its modes below the cut-off; then AMLS refined to
//! the residual check and counted by Sturm, beside flexmodes' Lanczos.

use serde_json::{Value, json};

use crate::scenes::{SceneInfo, SceneOptions, SceneOutput};
use crate::{
    Result,
    models::{
        LadderPoint, SubstructuringParameters, SubstructuringStudy, amls_json, substructuring_study,
    },
    record::{
        AMLS, Geometry, Layout, LogLogChart, LogLogSeries, REFERENCE, Visual, level_color,
        method_color,
    },
    reduction::Method,
    report::{Cell, Report, Table, readable, sig, sig_vec, sig3},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "amls",
    recording_cost: 4,
    summary: "multi-level substructuring (AMLS, Bennighof & Lehoucq 2004) on a refined App. B \
              slab: the nested-dissection tree level by level, Guyan and Craig-Bampton on its \
              root separator against AMLS over every level, and AMLS refined against Lanczos",
    sections: "§6.3–6.4; Bennighof & Lehoucq 2004",
    controls: crate::scenes::scene_info::SceneControls::NONE,
};

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let params = SubstructuringParameters::default();
    opts.progress.phase("substructure ladder")?;
    let study = substructuring_study(&params)?;
    let report = report(&study);
    let markdown = format!(
        "# amls\n\nThe ladder of component mode synthesis on one free body, the App. B slab \
         (4 × 2 × 1 m) meshed with {bx} × {by} × {bz} bricks ({dof} DOF). Nested dissection \
         cuts it in two by a plane of nodes, the **root separator**, then cuts each half again, \
         down to parts of at most {leaf} unknowns: the tree the sparse factorisation orders \
         its unknowns by. **Guyan** condenses the body onto the root separator (its two halves \
         follow statically); **Craig–Bampton** adds each half's fixed-interface modes below a \
         cut-off; **AMLS** (multi-level substructuring) treats every separator as an interface \
         in turn, from the leaves up, and keeps of every part and every separator only its own \
         modes below the cut-off, so the interface is reduced too. Each model is compared on \
         the body's lowest {wanted} elastic free-free frequencies; every reduced frequency lies \
         above the body's (Rayleigh–Ritz). Views: the tree, leaves grey and each level's \
         separators in its colour (`tree`); the largest relative frequency error against the \
         model's coordinates, one line per method through its cut-offs ({ratios} times the \
         highest compared frequency; log–log); the modes each level keeps at {shown} times \
         it.\n\n{table}",
        bx = params.bricks[0],
        by = params.bricks[1],
        bz = params.bricks[2],
        dof = study.model.dof_count(),
        leaf = params.leaf,
        wanted = params.wanted,
        ratios = params
            .cutoff_ratios
            .iter()
            .map(|r| readable(r, 2))
            .collect::<Vec<_>>()
            .join(", "),
        shown = readable(params.shown_ratio, 2),
        table = report.table,
    );
    let mut visuals = tree_visuals(&study);
    visuals.extend(ladder_chart(&study).visuals());
    visuals.push(level_bars(&study));
    let views = Layout::Vertical(
        vec![
            Layout::view3d("tree", "/world/tree"),
            Layout::Horizontal(
                vec![
                    Layout::Spatial2D {
                        name: "error against coordinates".into(),
                        origin: "/ladder".into(),
                    },
                    Layout::BarChart {
                        name: "modes per level".into(),
                        origin: "/levels".into(),
                        legend: false,
                    },
                ],
                vec![3.0, 2.0],
            ),
        ],
        vec![1.0, 1.0],
    );
    Ok(SceneOutput::beside_text(report, markdown, visuals, views))
}

/// Per level of the tree: parts, leaves among them, unknowns and modes kept.
fn levels(study: &SubstructuringStudy) -> Vec<[usize; 4]> {
    let depth = study.parts.iter().map(|p| p.level + 1).max().unwrap_or(0);
    let mut out = vec![[0; 4]; depth];
    for p in &study.parts {
        let row = &mut out[p.level];
        row[0] += 1;
        row[1] += usize::from(p.leaf);
        row[2] += p.unknowns;
        row[3] += p.modes;
    }
    out
}

fn point_json(p: &LadderPoint) -> Value {
    json!({
        "cutoff_hz": if p.cutoff_hz.is_finite() { json!(sig(p.cutoff_hz)) } else { Value::Null },
        "coordinates": p.coordinates,
        "hz": sig_vec(&p.hz),
        "max_rel_error": p.error.map(sig),
    })
}

fn report(study: &SubstructuringStudy) -> Report {
    let mut report = Report::new(INFO.name);
    insert_parameters(&mut report, study);
    insert_results(&mut report, study);
    let ladder_md = report.add_table(ladder_table(study));
    let tree_md = report.add_table(tree_table(study));
    report.table = scene_text(study, &ladder_md, &tree_md);
    report
}

/// The study's parameters: mesh, DOF, compared modes, leaf size and cut-off ratios.
fn insert_parameters(report: &mut Report, study: &SubstructuringStudy) {
    let params = &study.parameters;
    report
        .parameters
        .insert("bricks".into(), json!(params.bricks));
    report
        .parameters
        .insert("dof".into(), json!(study.model.dof_count()));
    report
        .parameters
        .insert("compared_modes".into(), json!(params.wanted));
    report
        .parameters
        .insert("leaf_unknowns".into(), json!(params.leaf));
    report
        .parameters
        .insert("cutoff_ratios".into(), json!(params.cutoff_ratios));
    report
        .parameters
        .insert("shown_ratio".into(), json!(params.shown_ratio));
}

/// The ladder's points, the tree's levels and the refined pairs' statistics.
fn insert_results(report: &mut Report, study: &SubstructuringStudy) {
    let params = &study.parameters;
    report
        .results
        .insert("reference_hz".into(), json!(sig_vec(&study.reference_hz)));
    report
        .results
        .insert("guyan".into(), point_json(&study.guyan));
    report.results.insert(
        "craig_bampton".into(),
        json!(
            study
                .craig_bampton
                .iter()
                .map(point_json)
                .collect::<Vec<_>>()
        ),
    );
    report.results.insert(
        "amls".into(),
        json!(study.amls.iter().map(point_json).collect::<Vec<_>>()),
    );
    let by_level = levels(study);
    report.results.insert(
        "tree".into(),
        json!({
            "levels": by_level.len(),
            "parts": study.parts.len(),
            "leaves": study.parts.iter().filter(|p| p.leaf).count(),
            "per_level": by_level.iter().enumerate().map(|(l, r)| json!({
                "level": l, "parts": r[0], "leaves": r[1], "unknowns": r[2], "modes": r[3],
            })).collect::<Vec<_>>(),
        }),
    );
    let r = &study.refined;
    let s = &r.statistics;
    let rigid = study.model.dofs.rigid_body_count();
    let mut refined = amls_json(s);
    for (key, value) in [
        ("pairs", json!(rigid + params.wanted)),
        ("eigenvalues_apart", json!(sig(r.apart))),
        ("sturm_missed", json!(r.missed)),
        ("amls_s", json!(sig(r.amls_s))),
        ("lanczos_s", json!(sig(r.lanczos_s))),
    ] {
        refined[key] = value;
    }
    report.results.insert("refined".into(), refined);
}

/// One row per model of the ladder: the body itself, Guyan, Craig–Bampton and AMLS at each
/// cut-off.
fn ladder_table(study: &SubstructuringStudy) -> Table {
    let mut ladder = Table::new(&[
        "model",
        "cut-off Hz",
        "coordinates",
        "max rel. error",
        "lowest elastic Hz",
    ])
    .rank_lower(&[3]);
    let row = |name: &str, p: &LadderPoint| {
        vec![
            Cell::text(name),
            if p.cutoff_hz.is_finite() {
                Cell::number(p.cutoff_hz, sig3(p.cutoff_hz))
            } else {
                Cell::text("–")
            },
            Cell::number(p.coordinates as f64, p.coordinates.to_string()),
            match p.error {
                Some(e) => Cell::number(e, sig3(e)),
                None => Cell::text("too few modes"),
            },
            Cell::text(
                p.hz.iter()
                    .map(|h| readable(h, 4))
                    .collect::<Vec<_>>()
                    .join(", "),
            ),
        ]
    };
    ladder.push(vec![
        Cell::text("body (Lanczos)"),
        Cell::text("–"),
        Cell::number(
            study.model.dof_count() as f64,
            study.model.dof_count().to_string(),
        ),
        Cell::text("–"),
        Cell::text(
            study
                .reference_hz
                .iter()
                .map(|h| readable(h, 4))
                .collect::<Vec<_>>()
                .join(", "),
        ),
    ]);
    ladder.push(row("Guyan", &study.guyan));
    for p in &study.craig_bampton {
        ladder.push(row("Craig–Bampton", p));
    }
    for p in &study.amls {
        ladder.push(row("AMLS", p));
    }
    ladder
}

/// One row per level of the tree.
fn tree_table(study: &SubstructuringStudy) -> Table {
    let by_level = levels(study);
    let mut tree = Table::new(&["level", "parts", "leaves", "unknowns", "modes kept"]);
    for (l, r) in by_level.iter().enumerate() {
        tree.push(
            [l, r[0], r[1], r[2], r[3]]
                .iter()
                .map(|&v| Cell::number(v as f64, v.to_string()))
                .collect(),
        );
    }
    tree
}

/// The scene's text around its two tables.
fn scene_text(study: &SubstructuringStudy, ladder_md: &str, tree_md: &str) -> String {
    let params = &study.parameters;
    let (r, s) = (&study.refined, &study.refined.statistics);
    let rigid = study.model.dofs.rigid_body_count();
    let shown_hz = params.shown_ratio * study.reference_hz.last().copied().unwrap_or(0.0);
    format!(
        "## The ladder\n\nThe largest relative error over the lowest {wanted} elastic \
         frequencies, paired by order. Guyan keeps the root separator's {root} DOF; \
         Craig–Bampton adds the halves' fixed-interface modes below the cut-off; AMLS keeps \
         only modes below the cut-off everywhere, interfaces included, so at one cut-off it \
         has fewer coordinates and a larger error: its accuracy is set by the cut-off, and its \
         gain is cost on large bodies, where every part is small and solved on its own.\n\n\
         {ladder_md}\n## The tree\n\nModes each level keeps below {shown} Hz (level 0 is the \
         root separator; the deepest levels are leaves).\n\n{tree_md}\n## Refined\n\nAMLS's \
         pairs are only as good as its cut-off, so flexmodes refines them (Rayleigh–Ritz with \
         the body's own K and M on the Ritz vectors, their images under AMLS's block factor \
         and the last step) until every residual ‖Kφ − λMφ‖/‖Kφ‖ is at most 1e-8, then counts \
         by Sturm. The lowest {pairs} pairs ({rigid} rigid): first cut-off {first} Hz, {reductions} \
         reduction(s), the last at {cutoff} Hz keeping {projected} modes; before refinement \
         the worst wanted eigenvalue was {unrefined} too high; {iterations} refinement steps \
         to a worst residual of {residual}; eigenvalues within {apart} of Lanczos', the Sturm \
         count missing {missed}. {amls_s} s against Lanczos' {lanczos_s} s on this body (one \
         process, its kernels on up to {threads} thread(s)); `flexmodes bench slab-modes --sizes 7k,28k \
         --eigensolver lanczos,amls` times both at scale (docs/amls.md).\n",
        wanted = params.wanted,
        root = study.guyan.coordinates,
        shown = sig3(shown_hz),
        pairs = rigid + params.wanted,
        first = sig3(shown_hz),
        reductions = s.reductions,
        cutoff = sig3(s.cutoff_hz),
        projected = s.projected,
        unrefined = sig3(s.unrefined_value_error),
        iterations = s.iterations,
        residual = readable(s.max_residual, 2),
        apart = readable(r.apart, 2),
        missed = r.missed,
        amls_s = sig3(r.amls_s),
        lanczos_s = sig3(r.lanczos_s),
        threads = crate::linalg::threads(),
    )
}

/// Each part of the tree drawn by the mesh edges inside it: leaves grey, each level's
/// separators in the level's colour, entities by level (`world/tree/level_2/...`) so that a
/// level can be hidden in the viewer; the root separator labelled.
fn tree_visuals(study: &SubstructuringStudy) -> Vec<Visual> {
    let model = &study.model;
    let mut part_of = vec![usize::MAX; model.node_count()];
    for (i, p) in study.parts.iter().enumerate() {
        for &n in &p.nodes {
            part_of[n] = i;
        }
    }
    let mut visuals = Vec::new();
    for (i, p) in study.parts.iter().enumerate() {
        let edges: Vec<[usize; 2]> = model
            .edges
            .iter()
            .filter(|e| part_of[e[0]] == i && part_of[e[1]] == i)
            .copied()
            .collect();
        let kind = if p.leaf { "leaf" } else { "separator" };
        visuals.push(Visual::Wireframe {
            path: format!("world/tree/level_{}/{kind}_{i}", p.level),
            geometry: Geometry::of_edges(model.nodes.clone(), &edges),
            color: if p.leaf {
                REFERENCE
            } else {
                level_color(p.level)
            },
            label: None,
        });
    }
    if let Some(root) = study.parts.last() {
        let n = root.nodes.len().max(1) as f64;
        let mut centre = [0.0; 3];
        for &j in &root.nodes {
            for (c, x) in centre.iter_mut().zip(model.nodes[j]) {
                *c += x / n;
            }
        }
        let top = model.nodes.iter().map(|x| x[2]).fold(f64::MIN, f64::max);
        visuals.push(Visual::Label3D {
            path: "world/tree/level_0/label".into(),
            position: [centre[0], centre[1], top + 0.3],
            text: format!(
                "root separator: {} DOF, {} modes kept",
                root.unknowns, root.modes
            ),
            color: level_color(0),
        });
    }
    visuals
}

/// The ladder on a log–log chart: error against coordinates, one series per method.
fn ladder_chart(study: &SubstructuringStudy) -> LogLogChart {
    let points = |ps: &[LadderPoint]| -> Vec<(f64, f64)> {
        ps.iter()
            .filter_map(|p| p.error.map(|e| (p.coordinates as f64, e)))
            .collect()
    };
    LogLogChart {
        path: "ladder".into(),
        x_unit: "coordinates".into(),
        y_unit: "max rel. freq. error".into(),
        series: vec![
            LogLogSeries {
                id: "guyan".into(),
                label: "Guyan".into(),
                color: method_color(Method::Guyan),
                points: points(std::slice::from_ref(&study.guyan)),
                line: false,
            },
            LogLogSeries {
                id: "craig_bampton".into(),
                label: "CB".into(),
                color: method_color(Method::CraigBampton),
                points: points(&study.craig_bampton),
                line: true,
            },
            LogLogSeries {
                id: "amls".into(),
                label: "AMLS".into(),
                color: AMLS,
                points: points(&study.amls),
                line: true,
            },
        ],
        x_linear: false,
    }
}

/// The modes each level keeps at the shown cut-off, one bar per level.
fn level_bars(study: &SubstructuringStudy) -> Visual {
    let by_level = levels(study);
    Visual::SeriesBars {
        path: "levels/modes".into(),
        abscissa: (0..by_level.len()).map(|l| l as f64).collect(),
        values: by_level.iter().map(|r| r[3] as f64).collect(),
        width: 0.6,
        color: AMLS,
    }
}
