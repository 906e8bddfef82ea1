//! The command line (`main.rs` only calls [`main`]).

mod arguments;
mod commands;

pub use arguments::Cli;
pub use commands::main;
