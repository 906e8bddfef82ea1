//! The classroom's data: Rerun's gRPC data server, fed the recordings of the scenes (each with
//! its blueprint) and of `.rrd` files; the students' web viewers connect to it and follow what
//! arrives. A teacher's command publishes a scene again with other options as a new recording.

use std::{net::IpAddr, path::Path};

use rerun::{
    external::{re_log_encoding::DecoderApp, re_log_types::LogMsg},
    grpc_server::GrpcServerSink,
    sink::LogSink as _,
};

use crate::{
    Result,
    error::{RecordingProblem, ServeError},
    record::Recorder,
    scenes::{Scene, SceneOptions},
};

/// The data server.
pub struct Classroom {
    sink: GrpcServerSink,
}

/// `rerun+http://ADDRESS:PORT/proxy`: where a viewer connects for the data.
pub fn data_url(address: IpAddr, port: u16) -> String {
    match address {
        IpAddr::V4(a) => format!("rerun+http://{a}:{port}/proxy"),
        IpAddr::V6(a) => format!("rerun+http://[{a}]:{port}/proxy"),
    }
}

impl Classroom {
    /// Starts the data server on `address:port`, admitting requests from the page `origins`
    /// beside Rerun's default (localhost, 127.0.0.1).
    pub fn start(address: IpAddr, port: u16, origins: Vec<String>) -> Result<Self> {
        let options = rerun::ServerOptions {
            cors_allowed_origins: origins,
            // Every recording is kept for viewers that join late.
            memory_limit: rerun::MemoryLimit::from_fraction_of_total(0.25),
            ..Default::default()
        };
        let sink = GrpcServerSink::new(&address.to_string(), port, options).map_err(|e| {
            ServeError::Bind {
                address,
                port: Some(port),
                source: Box::new(e),
            }
        })?;
        Ok(Self { sink })
    }

    /// Sends one recording's messages (and its blueprint's) to every viewer.
    pub fn publish(&self, messages: Vec<LogMsg>) {
        for m in messages {
            self.sink.send(m);
        }
        self.sink
            .flush_blocking(std::time::Duration::from_secs(10))
            .ok();
    }
}

/// A scene run with `options` as the messages of its recording and blueprint; `suffix` makes
/// its recording id new (a teacher's second showing of a scene).
pub fn scene_messages(
    scene: &Scene,
    options: &SceneOptions,
    suffix: Option<String>,
) -> Result<Vec<LogMsg>> {
    let out = scene.execute(options)?;
    Recorder {
        recording_suffix: suffix,
        default_blueprint_only: false,
        viewer_area: None,
    }
    .messages(&out)
}

/// The messages of an `.rrd` file, decoded whole: a file that does not decode to the end, or
/// holds no recording, is refused by name (Rerun's own `rrd verify` passes a file whose
/// header is right and whose body is garbage).
pub fn file_messages(path: &Path) -> Result<Vec<LogMsg>> {
    let refuse = |problem: RecordingProblem| -> crate::Error {
        ServeError::Recording {
            path: path.to_path_buf(),
            problem,
        }
        .into()
    };
    let bytes = std::fs::read(path).map_err(|e| refuse(RecordingProblem::Unreadable(e)))?;
    let mut messages = Vec::new();
    for (message, m) in DecoderApp::decode_lazy(bytes.as_slice()).enumerate() {
        messages.push(m.map_err(|e| {
            refuse(RecordingProblem::Damaged {
                message,
                source: Box::new(e),
            })
        })?);
    }
    let recordings = messages
        .iter()
        .filter(|m| matches!(m, LogMsg::SetStoreInfo(i) if i.info.store_id.is_recording()))
        .count();
    if recordings == 0 {
        return Err(refuse(RecordingProblem::NoRecording {
            messages: messages.len(),
        }));
    }
    let data = messages
        .iter()
        .filter(|m| matches!(m, LogMsg::ArrowMsg(..)))
        .count();
    if data == 0 {
        return Err(refuse(RecordingProblem::NoData));
    }
    Ok(messages)
}
