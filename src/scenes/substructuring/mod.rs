//! Substructuring: multi-level substructuring (AMLS), the last rung of the component-mode
//! ladder.

pub(super) mod amls;
