//! The Rerun SDK as the recorder uses it: `re_sdk` (recording streams, `.rrd` encoding, the
//! blueprint) and `re_sdk_types` (archetypes, components, datatypes), the two crates the
//! `rerun` crate's `sdk` feature re-exports. The command line depends on these two alone, not
//! on `rerun`, which always brings what a recorder never uses (the catalogue client with its
//! TLS stack, the chunk store, analytics): 74 crates fewer to build before a first result.
//! The explorer and the classroom depend on `rerun` for its viewer and server; its SDK types
//! are these.

pub use re_sdk::{
    ApplicationId, AsComponents, RecordingStream, RecordingStreamBuilder, RecordingStreamError,
    SerializationError, blueprint, external,
    log::{Chunk, TimeColumn},
};
pub use re_sdk_types::{
    archetypes::{
        Arrows3D, BarChart, LineStrips2D, LineStrips3D, Points2D, Points3D, Scalars, SeriesLines,
        TextDocument, Transform3D, ViewCoordinates,
    },
    blueprint::archetypes as blueprint_archetypes,
    components::{Color, Radius},
    datatypes,
};
