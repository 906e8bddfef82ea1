//! The one recorder used by the CLI (and the GUI): scene visuals to Rerun entities, the default
//! blueprint, and atomic `.rrd` writing.

mod layout;
mod recorder;
mod visual;

pub use layout::Layout;
pub use recorder::{Recorder, write_atomically};
pub use visual::{Color, Geometry, PHASE_STEPS, Visual};
