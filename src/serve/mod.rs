//! `flexmodes serve` (feature `serve`): the classroom in the browser. The embedded Rerun web
//! viewer served over HTTP (offline, gzip), the scenes' recordings over Rerun's gRPC data
//! server, one URL for the students.

mod classroom;
mod page_url;
mod viewer_files;
mod web_server;

pub use classroom::{Classroom, data_url, file_messages, scene_messages};
pub use page_url::{origin, page_url};
pub use viewer_files::{ViewerFile, ViewerFiles, offline_index};
pub use web_server::{WebServer, check_port};
