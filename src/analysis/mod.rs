//! Analyses on bodies and bases: natural frequencies, deformed profiles (§7.1), subspaces.

mod frequencies;
mod mean_axes;
mod profiles;

pub use frequencies::{
    RIGID_BODY_HZ, elastic_hz, free_free_modes, lowest_free_free_modes, reduced_hz, reduced_modes,
};
pub use mean_axes::{MeanAxesEvaluation, evaluate_with_mean_axes, rigid_modes_about_mass_centre};
pub use profiles::{PROFILE_DELTA, ProfileFit, fit_given_modal_coordinates, fit_least_squares};
