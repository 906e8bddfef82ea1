//! What one recording holds.

use super::{Layout, Visual};
use crate::report::Report;

/// Everything one recording holds: the numbers, the text panel, the visuals and the default
/// layout. Scenes produce it (as `scenes::SceneOutput`); the recorder logs it.
#[derive(Debug, Clone)]
pub struct RecordingContent {
    /// The numeric report.
    pub report: Report,
    /// Markdown for the `scene` panel: what it shows, parameters, result table.
    pub markdown: String,
    /// What to log.
    pub visuals: Vec<Visual>,
    /// The default blueprint.
    pub layout: Layout,
    /// The timeline the time panel starts on (`phase` or `sim_time`); `None` for static scenes,
    /// whose time panel is collapsed.
    pub timeline: Option<String>,
    /// Planar scenes (the beam in the x-y plane) declare y up, so the 3D views face the plane;
    /// solids declare z up.
    pub y_up: bool,
}
