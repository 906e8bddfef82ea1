//! Analyses on bodies, bases and simulations: natural frequencies, deformed profiles (§7.1),
//! mean-axis evaluation (§8.4), simulation measures (§7.2, §5.3.3), static responses.

mod dynamic_compliance;
mod frequencies;
mod frequency_response;
mod mean_axes;
mod mean_axis_view;
mod mode_pairing;
mod pareto;
mod profiles;
mod simulation_metrics;
mod static_response;

pub use dynamic_compliance::{
    RESONANCE_CLEARANCE, full_dynamic_compliance, off_resonance_frequencies,
    reduced_dynamic_compliance,
};
pub use frequencies::{
    ZeroEnergyCount, count_zero_energy_modes, count_zero_energy_modes_by, elastic_hz,
    free_free_modes, lowest_free_free_modes, reduced_hz, reduced_modes, zero_energy_below,
    zero_energy_threshold_hz,
};
pub use frequency_response::{FrequencyResponse, band_frequencies, modes_in_band};
pub use mean_axes::{MeanAxesEvaluation, evaluate_with_mean_axes, rigid_modes_about_mass_centre};
pub use mean_axis_view::MeanAxisView;
pub use mode_pairing::{MAC_ACCURATE, ModePair, mac, mac_matrix, pair_modes};
pub use pareto::{pareto_flags, three_digits};
pub use profiles::{PROFILE_DELTA, ProfileFit, fit_given_modal_coordinates, fit_least_squares};
pub use simulation_metrics::{
    max_energy_drift, max_position_violation, max_until, mirror_defect_history,
    node_deflection_history, relative_rms,
};
pub use static_response::{
    StaticLoadCase, full_static_response, relative_error, ritz_static_response,
};
