//! The companion papers' scenes: Spanos–Tsuha's mode sets on a dual-spin assembly and
//! Witteveen's cantilever variants.

pub(super) mod cantilever_text;
pub mod cantilever_variants;
pub(super) mod cantilever_views;
pub(super) mod slab_mode_set_views;
pub mod slab_mode_sets;
