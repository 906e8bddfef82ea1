//! The scene report a recording holds (its `report` entity, written by the recorder): what
//! `flexmodes diff` compares when handed `.rrd` files.

use std::path::Path;

use serde_json::Value;

use super::recording_digest::ENTITY_PATH;
use super::rerun_sdk::Chunk;
use super::rerun_sdk::external::{re_log_encoding::DecoderApp, re_log_types::LogMsg};
use crate::{Error, Result, error::ReportDiffError};

/// Entity path of a recording's report: `report --json`'s object as text.
pub const REPORT_ENTITY: &str = "report";

/// The report in the recording at `path`: the last text logged to [`REPORT_ENTITY`], parsed.
/// A file that does not decode, or holds no report (a recording made before reports were
/// recorded, or by another program), is [`ReportDiffError::NoReport`].
pub fn recorded_report(path: &Path) -> Result<Value> {
    let name = path.display().to_string();
    let no_report = |why: String| -> Error {
        ReportDiffError::NoReport {
            path: name.clone(),
            why,
        }
        .into()
    };
    let bytes = std::fs::read(path).map_err(|source| Error::io(path.to_path_buf(), source))?;
    let mut text = None;
    let entity = format!("/{REPORT_ENTITY}");
    for (index, message) in DecoderApp::decode_lazy(bytes.as_slice()).enumerate() {
        let message =
            message.map_err(|e| no_report(format!("message {index} does not decode: {e}")))?;
        let LogMsg::ArrowMsg(store, arrow) = &message else {
            continue;
        };
        // Only the report's chunks are decoded: the entity path is in the batch's metadata.
        let schema = arrow.batch.schema();
        let path = schema.metadata().get(ENTITY_PATH).map(String::as_str);
        if store.is_blueprint() || path != Some(entity.as_str()) {
            continue;
        }
        let chunk = Chunk::from_arrow_msg(arrow)
            .map_err(|e| no_report(format!("message {index} is no chunk: {e}")))?;
        if chunk.entity_path().to_string() != entity {
            continue;
        }
        let component = super::rerun_sdk::TextDocument::descriptor_text().component;
        for batch in chunk.iter_slices::<String>(component) {
            if let Some(last) = batch.last() {
                text = Some(last.to_string());
            }
        }
    }
    let text = text.ok_or_else(|| {
        no_report(format!(
            "the recording has no `{REPORT_ENTITY}` entity (recorded before flexmodes wrote \
             one, or not by flexmodes)"
        ))
    })?;
    serde_json::from_str(&text).map_err(|e| no_report(format!("its report is not JSON: {e}")))
}
