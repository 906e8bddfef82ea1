//! The command line (`main.rs` only calls [`main`]).

mod arguments;
mod commands;
mod serve;
mod simulate;
mod stderr;

pub use arguments::Cli;
pub use commands::main;
