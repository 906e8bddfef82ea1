//! Messages of the command line on stderr.

use std::io::IsTerminal;

/// A progress message on stderr, only when a person watches it (a terminal).
pub(super) fn progress(msg: &str) {
    if std::io::stderr().is_terminal() {
        eprintln!("{msg}");
    }
}
