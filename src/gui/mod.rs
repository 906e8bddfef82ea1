//! The desktop explorer (feature `gui`): the Rerun viewer embedded beside an egui panel whose
//! controls recompute the scene on a worker thread.
//!
//! [`Explorer`] holds everything but the viewer, so headless tests drive it with egui_kittest;
//! [`run`] wraps it with the viewer in a native window.

mod anticipation;
mod app;
mod capture;
mod controls;
mod explorer;
mod explorer_error;
mod model_panel;
mod report_view;
mod simulation_controls;
mod simulation_panel;
mod updating_badge;
mod viewer_handoff;
mod worker;

pub use app::{FEWER_MODES, MORE_MODES, VIEWER_AREA, ViewerOptions, run, run_with_body};
pub use capture::FrameSeries;
pub use controls::{Change, Command, Controls, MESH_PRESETS};
pub use explorer::Explorer;
pub use explorer_error::ExplorerError;
pub use simulation_controls::{DriveMotion, SimulationControls};
pub use viewer_handoff::{HandoffState, Offer, ViewerHandoff};
pub use worker::{Computed, Finished, Worker};
