//! Spinning: dynamic stiffening, the Campbell diagram and Kane's spin-up.

pub(super) mod spin_up;
