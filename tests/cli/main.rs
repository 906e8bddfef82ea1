//! The command line as users and CI run it: exit codes, JSON keys, atomic writes; one module
//! per family of commands.

#[path = "../common/cli.rs"]
#[allow(dead_code)]
mod common;
#[path = "../common/scratch.rs"]
mod scratch;

mod bench;
mod bodies;
mod diff;
mod scenes;
mod simulate;

pub(crate) const SCENES: [&str; 15] = [
    "beam-modes",
    "slab-modes",
    "beam-profiles",
    "beam-eitelberg",
    "slab-sim1",
    "slab-sim2",
    "slab-sim3",
    "plank-symmetry",
    "beam-mean-axes",
    "failures",
    "modes",
    "slab-mode-sets",
    "cantilever-variants",
    "spin-up",
    "amls",
];
