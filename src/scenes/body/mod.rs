//! A user's body: its modes under every method, its interfaces' responses and its driven
//! simulation.

pub(super) mod body_influence;
pub mod body_modes;
pub(super) mod body_modes_report;
pub(super) mod body_modes_text;
pub(super) mod body_response;
pub mod body_simulation;
pub(super) mod body_simulation_report;
pub(super) mod body_simulation_visuals;
