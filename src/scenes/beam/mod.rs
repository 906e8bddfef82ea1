//! The App. A beam's scenes: its mode sets, deformed profiles, Eitelberg's method and mode
//! condensation with mean axes (chapters 6–8).

pub(super) mod beam_eitelberg;
pub(super) mod beam_mean_axes;
pub(super) mod beam_modes;
pub(super) mod beam_profiles;
mod beam_run;
