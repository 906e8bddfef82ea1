//! The scene registry behind `flexmodes list`, `record` and `report`.

mod beam_eitelberg;
mod beam_mean_axes;
mod beam_modes;
mod beam_profiles;
mod body_influence;
pub mod body_modes;
mod body_modes_report;
mod body_response;
pub mod body_simulation;
mod body_simulation_visuals;
mod cantilever_text;
pub mod cantilever_variants;
mod cantilever_views;
mod failure_cases;
mod failure_motion_cases;
mod failures;
mod frequency_bars;
mod mode_visuals;
mod options;
pub mod plank_symmetry;
mod registry;
mod run_cache;
mod scene_info;
mod sim_visuals;
mod slab_mode_set_views;
pub mod slab_mode_sets;
mod slab_mode_views;
mod slab_modes;
mod slab_refined;
mod slab_sim_report;
mod slab_sim_views;
pub mod slab_sims;

pub use options::{SceneOptions, SceneOutput};
pub use registry::{Scene, all, all_ids, find, ids};
pub use run_cache::{CacheWeight, RunCache};
pub use scene_info::{SceneControls, SceneInfo};
