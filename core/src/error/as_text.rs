//! How an error value that is not serialisable itself (an I/O error, another library's
//! error) enters an error's JSON: as its message.

/// `e` as its message.
pub(super) fn as_text<S: serde::Serializer, E: std::fmt::Display + ?Sized>(
    e: &E,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    s.collect_str(e)
}
