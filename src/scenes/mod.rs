//! The scene registry behind `flexmodes list`, `record` and `report`.

mod beam;
mod body;
mod companion;
mod failures;
mod frequency_bars;
mod mode_visuals;
mod options;
mod registry;
mod run_cache;
mod scene_id;
mod scene_info;
mod scene_option;
mod slab;
mod spinning;
mod substructuring;

pub use body::{body_modes, body_simulation};
pub use companion::{cantilever_variants, slab_mode_sets};
pub use options::{SceneOptions, SceneOutput};
pub use registry::{Scene, SceneId, all, all_ids, find, get};
pub use run_cache::{CacheWeight, RunCache};
pub use scene_info::{SceneControls, SceneInfo};
pub use scene_option::SceneOption;
pub use slab::{plank_symmetry, slab_sims};
