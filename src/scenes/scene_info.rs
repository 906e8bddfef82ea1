//! What a scene is and which options it offers, as `flexmodes list` and the explorer's panel
//! show them.

use super::SceneId;
use crate::{dynamics::AxisKind, reduction::Method};

/// Static description of a scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneInfo {
    /// Which scene (its text form names recordings and tables).
    pub id: SceneId,
    /// One line for `flexmodes list`.
    pub summary: &'static str,
    /// Thesis sections it reproduces.
    pub sections: &'static str,
    /// What the scene's options can be set to (for the desktop panel).
    pub controls: SceneControls,
}

/// The options a scene offers and their defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneControls {
    /// Methods that can be shown.
    pub methods: &'static [Method],
    /// Default boundary/master nodes (empty: the scene has no boundary choice).
    pub boundary: &'static [usize],
    /// Default kept normal modes (`None`: the scene keeps none).
    pub modes: Option<usize>,
    /// Axis types offered (empty: no floating frame).
    pub axes: &'static [AxisKind],
    /// Default simulated interval, s (`None`: not a simulation).
    pub end_time: Option<f64>,
    /// Default mesh as bricks along x, y, z (`None`: the scene's body cannot be refined).
    pub refine: Option<[usize; 3]>,
}

impl SceneControls {
    /// A scene whose only choice is which of `methods` to show (no boundary, kept modes, axes,
    /// interval or mesh): the companion papers' fixed experiments, the failures catalogue.
    pub const fn methods_only(methods: &'static [Method]) -> Self {
        Self {
            methods,
            boundary: &[],
            modes: None,
            axes: &[],
            end_time: None,
            refine: None,
        }
    }
}
