//! `flexmodes serve` (feature `serve`): the classroom in the browser. The embedded Rerun web
//! viewer served over HTTP (offline, gzip), the scenes' recordings over Rerun's gRPC data
//! server, one URL for the students, and the teacher's control page behind a token.

mod classroom;
mod control_page;
mod page_url;
mod publisher;
mod viewer_files;
mod web_server;

pub use classroom::{Classroom, data_url, file_messages, scene_messages};
pub use control_page::{
    CONTROL_FIELDS, ControlAnswer, ControlApply, ControlPage, MAX_CONTROL_BODY, html_escape,
    new_control_token,
};
pub use page_url::{origin, page_url};
pub use publisher::{PublishJob, PublishStatus, Publisher};
pub use viewer_files::{ViewerFile, ViewerFiles, offline_index};
pub use web_server::{WebServer, check_port};
