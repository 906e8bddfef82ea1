//! Where a body file and the files it names are read from: a path on disk, a body embedded
//! in the binary, or text in memory.

use std::path::{Path, PathBuf};

use super::BodyFileError;
use crate::error::BodySpecProblem;
use crate::{Error, Result};

/// Where a body file and the files it names are read from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BodyLocation {
    /// A body file on disk; the files it names are relative to its folder.
    Disk(PathBuf),
    /// A body embedded in the binary (`builtin:NAME`, from `assets/bodies/NAME/`).
    Builtin(String),
    /// A body handed over in memory ([`ImportedBody::from_matrices`](super::ImportedBody::from_matrices), Python's
    /// `flexmodes.Body`): its name; it names no other file.
    Memory(String),
}

impl BodyLocation {
    /// `builtin:NAME` for an embedded body, a path otherwise.
    pub fn parse(s: &str) -> Self {
        match s.strip_prefix("builtin:") {
            Some(name) => Self::Builtin(name.to_string()),
            None => Self::Disk(PathBuf::from(s)),
        }
    }

    /// The body file itself, as shown in messages.
    pub fn display(&self) -> String {
        match self {
            Self::Disk(p) => p.display().to_string(),
            Self::Builtin(name) => format!("builtin:{name}"),
            Self::Memory(name) => format!("<{name} in memory>"),
        }
    }

    /// Reads the body file (`None`) or a file it names, relative to it; returns the bytes and
    /// the name used in error messages.
    pub(super) fn read(&self, relative: Option<&str>) -> Result<(Vec<u8>, String)> {
        match self {
            Self::Disk(body) => {
                let path = match relative {
                    None => body.clone(),
                    Some(r) => body.parent().unwrap_or(Path::new(".")).join(r),
                };
                let bytes = std::fs::read(&path).map_err(|source| Error::Io {
                    path: path.clone(),
                    source,
                })?;
                Ok((bytes, path.display().to_string()))
            }
            Self::Memory(name) => Err(Error::BodyFile(BodyFileError::BodyFile {
                path: format!("<{name} in memory>").into(),
                line: None,
                problem: BodySpecProblem::NoFileInMemory {
                    asked: relative.map(crate::error::Name::from),
                },
            })),
            Self::Builtin(name) => {
                let file = relative.unwrap_or("body.toml");
                let asset = format!("bodies/{name}/{file}");
                let bytes = crate::assets::get(&asset).ok_or_else(|| {
                    Error::BodyFile(BodyFileError::BodyFile {
                        path: format!("builtin:{name}").into(),
                        line: None,
                        problem: BodySpecProblem::NoEmbeddedFile {
                            asset: (&asset).into(),
                            builtin: crate::assets::builtin_bodies(),
                        },
                    })
                })?;
                Ok((bytes.to_vec(), format!("assets/{asset}")))
            }
        }
    }
}
