//! A name a user gave, as an error quotes it.

use std::sync::Arc;

/// A name a user gave (a body, a node set, a ring, an interface, a matrix in a file, an
/// output), as an error carries it: shared, so an error that names a body clones a pointer,
/// and typed, so an error's fields say which of its strings are names and which are
/// [`Excerpt`](super::Excerpt)s of a file. Displayed as given; the message quotes it.
#[derive(Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Name(Arc<str>);

impl Name {
    /// `names` as [`Name`]s.
    pub fn all<S: AsRef<str>>(names: impl IntoIterator<Item = S>) -> Vec<Name> {
        names.into_iter().map(|n| Name::from(n.as_ref())).collect()
    }
}

/// `names` joined by `, `.
pub(super) fn joined(names: &[Name]) -> String {
    let names: Vec<&str> = names.iter().map(Name::as_str).collect();
    names.join(", ")
}

impl From<&str> for Name {
    fn from(name: &str) -> Self {
        Self(name.into())
    }
}

impl From<&Name> for Name {
    fn from(name: &Name) -> Self {
        name.clone()
    }
}

super::str_newtype::str_newtype!(Name);
