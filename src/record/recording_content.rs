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

impl RecordingContent {
    /// A recording of `report`, its text panel `markdown` and `visuals` in `layout`: static
    /// (no timeline) and z up, until [`Self::on_timeline`] and [`Self::y_up`] say otherwise.
    pub fn new(report: Report, markdown: String, visuals: Vec<Visual>, layout: Layout) -> Self {
        Self {
            report,
            markdown,
            visuals,
            layout,
            timeline: None,
            y_up: false,
        }
    }

    /// [`Self::new`] with `views` to the left of the text panel, three parts to its two: the
    /// layout most scenes share.
    pub fn beside_text(
        report: Report,
        markdown: String,
        visuals: Vec<Visual>,
        views: Layout,
    ) -> Self {
        Self::new(report, markdown, visuals, Layout::beside_text(views))
    }

    /// The time panel starts on `timeline` (`phase`, `sim_time`).
    pub fn on_timeline(mut self, timeline: &str) -> Self {
        self.timeline = Some(timeline.into());
        self
    }

    /// A planar body in the x-y plane: the 3D views face it.
    pub fn y_up(mut self) -> Self {
        self.y_up = true;
        self
    }
}
