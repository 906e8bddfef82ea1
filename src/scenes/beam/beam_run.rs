//! What the App. A beam's scenes start from: their default controls (boundary nodes 1 and 5,
//! two kept normal modes, §6.3–6.5) and, for a run, the options checked against them, the
//! beam and its partition, and the report's parameters.

use serde_json::json;

use crate::{
    Result,
    fem::{BeamParameters, FeModel, beam},
    reduction::{Method, Partition},
    report::Report,
    scenes::{SceneControls, SceneInfo, SceneOptions},
};

/// The beam's controls for `methods`: boundary 1, 5 and two kept modes.
pub(super) const fn beam_controls(methods: &'static [Method]) -> SceneControls {
    SceneControls {
        methods,
        boundary: &[1, 5],
        modes: Some(2),
        ..SceneControls::NONE
    }
}

/// One run of a beam scene: the methods, boundary and kept modes asked for (or the scene's
/// defaults), the App. A beam and its partition.
pub(super) struct BeamRun {
    /// The methods to compute, in the scene's order.
    pub methods: Vec<Method>,
    /// Boundary nodes, 1-based.
    pub boundary: Vec<usize>,
    /// Kept fixed-interface normal modes.
    pub kept: usize,
    /// The App. A beam.
    pub model: FeModel,
    /// Its boundary and interior, checked first so that a bad set's error names the cause.
    pub part: Partition,
}

impl BeamRun {
    /// The run `opts` asks of the scene `info` offering `available` methods (`default` when
    /// none is asked for).
    pub fn new(
        opts: &SceneOptions,
        info: &SceneInfo,
        (available, default): (&[Method], &[Method]),
    ) -> Result<Self> {
        let methods = opts.methods_or(info.name, available, default)?;
        let boundary = opts.boundary_or_default(info);
        let kept = opts.modes_or_default(info);
        let model = beam(&BeamParameters::default());
        let part = Partition::new(&model, &boundary)?;
        Ok(Self {
            methods,
            boundary,
            kept,
            model,
            part,
        })
    }

    /// The methods, boundary, kept modes, beam and partition, in that order.
    pub fn into_parts(self) -> (Vec<Method>, Vec<usize>, usize, FeModel, Partition) {
        (
            self.methods,
            self.boundary,
            self.kept,
            self.model,
            self.part,
        )
    }

    /// The scene's report with the run's boundary, kept modes and methods as parameters.
    pub fn report(&self, info: &SceneInfo) -> Report {
        let mut report = Report::new(info.name);
        let p = &mut report.parameters;
        p.insert("boundary".into(), json!(self.boundary));
        p.insert("modes".into(), json!(self.kept));
        p.insert(
            "methods".into(),
            json!(self.methods.iter().map(|m| m.id()).collect::<Vec<_>>()),
        );
        report
    }
}
