//! The App. B slab's scenes: its mode sets (on a refined mesh too), the §7.2 simulations and
//! the §5.3.3 hung plank.

pub mod plank_symmetry;
pub(super) mod sim_visuals;
pub(super) mod slab_mode_results;
pub(super) mod slab_mode_views;
pub(super) mod slab_modes;
pub(super) mod slab_refined;
pub(super) mod slab_sim_report;
pub(super) mod slab_sim_views;
pub mod slab_sims;
