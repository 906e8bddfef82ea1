//! The slow library tests, in their own binary so `cargo test` stays the quick check (Cargo.toml
//! leaves this target out of it: `test = false`). CI runs them:
//!
//! ```sh
//! cargo test --test slow
//! ```
//!
//! Each takes 5–50 s in the debug build: every reduction method against SciPy/LAPACK on the
//! committed external bodies, rigid interfaces against SciPy's transformed body, the static
//! compliance across an interface, the driven body's spin-up against SciPy's, and the
//! commands that reduce a whole external body (`report modes`, `export`, `bench modes`).

#[path = "../external/checks.rs"]
#[allow(dead_code)]
mod checks;

#[path = "../common/cli.rs"]
#[allow(dead_code)]
mod cli_common;
#[path = "../common/scratch.rs"]
mod scratch;

mod body_methods;
mod charts;
mod cli;
mod driven_body;
mod external_bodies;
