//! The one recorder used by the CLI and the GUI: visuals to Rerun entities, the default
//! blueprint, and atomic `.rrd` writing. It knows nothing of scenes: it logs a
//! [`RecordingContent`].

mod blueprint;
mod blueprint_key;
mod chart_text_check;
mod eye;
mod layout;
mod log_log_chart;
mod palette;
mod recorded_report;
mod recorder;
mod recording_content;
mod recording_digest;
mod rerun_sdk;
mod visual;
mod visual_log;

pub use blueprint_key::BlueprintKey;
pub use chart_text_check::{VIEW_PIXELS, chart_count, chart_text_clashes, chart_text_clashes_at};
pub use eye::{Bounds, Eye};
pub use layout::Layout;
pub use log_log_chart::{LogLogChart, LogLogSeries};
pub use palette::{
    AMLS, PARETO, REFERENCE, REFERENCE_GHOST, RESIDUAL_VECTORS, level_color, method_color,
};
pub use recorded_report::{REPORT_ENTITY, recorded_report};
pub use recorder::{Recorder, encode_messages};
pub use recording_content::RecordingContent;
pub use recording_digest::RecordingDigest;
pub use visual::{Color, GRID_LINE, Geometry, LINE, PHASE_STEPS, Visual};
