//! The command line (`main.rs` only calls [`main`]).

mod arguments;
mod bench;
mod body_arguments;
mod campbell;
mod commands;
mod diff;
mod serve;
mod simulate;
mod stderr;

pub use arguments::Cli;
pub use commands::main;
