//! An id on the command line or in a file that names no known method, integrator, axis type
//! or format.

/// `id` is not one of the `known` ids of `what`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error, serde::Serialize)]
#[error("unknown {what} `{id}` (known: {})", known.join(", "))]
pub struct UnknownId {
    /// What was named: `method`, `integrator`, `axis type`, `Ψ format`.
    pub what: &'static str,
    /// The id given.
    pub id: super::Excerpt,
    /// The known ids.
    pub known: Vec<&'static str>,
}

impl UnknownId {
    /// `id` is not among `known`.
    pub fn new(what: &'static str, id: &str, known: &[&'static str]) -> Self {
        Self {
            what,
            id: id.into(),
            known: known.to_vec(),
        }
    }
}
