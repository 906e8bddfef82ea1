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
//! - A spun arm's own inertia loads are missed by CB's fixed-interface modes alone; their
//!   residual vectors carry them (CalculiX's lever).

use crate::scenes::failures::failure_cases::{
    Failure, condensation_failure, eitelberg_failure, guyan_symmetry_failure,
    too_few_boundary_failure,
};
use crate::scenes::failures::failure_inertia_case::inertia_load_failure;
use crate::scenes::failures::failure_motion_cases::{
    boundary_motion_failure, explicit_step_failure, guyan_mean_axes_failure, spin_up_failure,
};
use crate::scenes::{SceneInfo, SceneOptions, SceneOutput};
use crate::{
    Result,
    fem::{BeamParameters, SlabParameters, beam, slab},
    models::MOVED_NODE,
    record::Layout,
    report::{Report, Table},
};

pub const INFO: SceneInfo = SceneInfo {
    name: "failures",
    recording_cost: 2,
    summary: "where the methods fail, in one recording: CB with too few boundary DOF, \
              Eitelberg without feedback, mode condensation's n³ cost, mean axes with a \
              Guyan mass, an explicit step above critical, Guyan (b)'s symmetry, modal \
              truncation and boundary motion, a spun arm's inertia loads without residual \
              vectors",
    sections: "§3.2, §4.2, §6.2–6.6, §7.1–7.2",
    controls: crate::scenes::scene_info::SceneControls::methods_only(
        &[],
        "the failures scene has fixed settings: each failure states its own",
    ),
};

pub fn run(opts: &SceneOptions) -> Result<SceneOutput> {
    let beam_model = beam(&BeamParameters::default());
    let slab_model = slab(&SlabParameters::default());
    let mut report = Report::new(INFO.name);
    let mut lines: Vec<[String; 3]> = Vec::new();
    let mut visuals = Vec::new();

    type Study<'a> = Box<dyn Fn() -> Result<Failure> + 'a>;
    let studies: [(&str, &str, Study); 9] = [
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
        (
            "spin_up_without_stiffening",
            "spin-up without dynamic stiffening",
            Box::new(|| spin_up_failure(opts)),
        ),
        (
            "inertia_loads_without_residual_vectors",
            "a spun arm's inertia loads",
            Box::new(|| inertia_load_failure(&opts.progress)),
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
    let markdown = scene_text(&lines);
    let views = failure_views();
    Ok(SceneOutput::beside_text(report, markdown, visuals, views).on_timeline("phase"))
}

/// The scene's text: what each view shows, then one section per failure (the panel is narrow
/// for the three-column table).
fn scene_text(lines: &[[String; 3]]) -> String {
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
    format!(
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
         below and above the critical one (log scale: the growth is a straight line). \
         *inertia loads*: the spun lever's tip history error against NR (lines) and the \
         a-priori estimate (points) for CB k without and with residual vectors (log–log).\n\n\
         {sections}"
    )
}

/// The two 3-D views above the three charts, each set as tabs.
fn failure_views() -> Layout {
    Layout::Vertical(
        vec![
            Layout::Tabs(vec![
                Layout::view3d("guyan (b) symmetry", "/modes"),
                Layout::view3d("boundary motion", "/static"),
            ]),
            Layout::Tabs(vec![
                Layout::Spatial2D {
                    name: "cost: offline s against DOF (log–log)".into(),
                    origin: "/charts/cost".into(),
                },
                Layout::Spatial2D {
                    name: "explicit step: node 8 |ζ| against time (semi-log)".into(),
                    origin: "/charts/explicit_step".into(),
                },
                Layout::Spatial2D {
                    name: "inertia loads: error and estimate against k (log–log)".into(),
                    origin: "/charts/inertia_loads".into(),
                },
            ]),
        ],
        vec![1.2, 1.0],
    )
}
