//! Recording content → Rerun recording (in memory), and atomic `.rrd` writing.

use std::path::Path;

use super::rerun_sdk::{
    self, RecordingStream, RecordingStreamBuilder,
    external::{re_log_encoding::Encoder, re_log_types::LogMsg},
};

use super::{
    BlueprintKey, Bounds, Eye, Layout, RecordingContent,
    blueprint::{BlueprintParameters, send_blueprint},
    visual_log::{OrRerun, log_visual},
};
use crate::{Error, Result};

/// The bytes of an `.rrd` file holding `messages` (see [`Recorder::messages`]).
pub fn encode_messages(messages: &[LogMsg]) -> Result<Vec<u8>> {
    Encoder::encode(messages.iter().map(Ok)).map_err(|e| Error::rerun("encode", e))
}

/// Prefix of every recording's application id (`flexmodes-<scene>`: one default layout per
/// scene in the viewer).
pub const APPLICATION_ID: &str = "flexmodes";

/// Turns a [`RecordingContent`] into Rerun data. Used by the CLI and the desktop app alike.
#[derive(Debug, Clone, Default)]
pub struct Recorder {
    /// Appended to the recording id, so successive recordings of one scene in the desktop
    /// app are distinct stores.
    pub recording_suffix: Option<String>,
    /// Send the blueprint as the application's default only, not active (the desktop app
    /// activates it itself once the whole recording is in the viewer). Files get it as the
    /// active blueprint.
    pub default_blueprint_only: bool,
    /// The viewer's area for views, points (`None`: a 1280 × 800 window of the standalone
    /// viewer): tab titles that would be cut there are shortened, and the scene text lists
    /// them in full.
    pub viewer_area: Option<(f64, f64)>,
}

impl Recorder {
    /// Encodes the scene as the bytes of an `.rrd` file (recording plus default blueprint).
    /// Log time is disabled so two runs give the same data.
    pub fn encode(&self, out: &RecordingContent) -> Result<Vec<u8>> {
        encode_messages(&self.messages(out)?)
    }

    /// The scene as the messages of a recording (plus its blueprint), not encoded: what the
    /// desktop app hands its embedded viewer. Encoding them into `.rrd` bytes cost about half
    /// of building them (15 of 28 ms on slab-sim1), and decoding again 5–8 ms more.
    pub fn messages(&self, out: &RecordingContent) -> Result<Vec<LogMsg>> {
        let id = match &self.recording_suffix {
            Some(s) => format!("flexmodes-{}-{s}", out.report.scene),
            None => format!("flexmodes-{}", out.report.scene),
        };
        let app_id = rerun_sdk::ApplicationId::new_or_unknown(format!(
            "{APPLICATION_ID}-{}",
            out.report.scene
        ));
        let (rec, storage) = RecordingStreamBuilder::new(app_id)
            .recording_id(id)
            .recording_name(out.report.scene.clone())
            .memory()
            .or_rerun()?;
        rec.set_log_time_enabled(false);
        rec.send_recording_name(out.report.scene.clone())
            .or_rerun()?;
        self.log(&rec, out)?;
        rec.flush_blocking().map_err(|e| Error::rerun("flush", e))?;
        Ok(storage.take())
    }

    /// Encodes and writes to `path` atomically (temporary file, then rename).
    pub fn save(&self, out: &RecordingContent, path: &Path) -> Result<()> {
        let bytes = self.encode(out)?;
        Ok(crate::atomic_file::write_bytes_atomically(path, &bytes)?)
    }

    /// The viewer's area for views, points.
    pub fn area(&self) -> (f64, f64) {
        self.viewer_area.unwrap_or(super::blueprint::VIEWPORT)
    }

    /// `out`'s layout with the tab titles that would be cut in [`Self::area`] shortened, and
    /// each shortened title with its full one.
    pub fn fitted_layout(&self, out: &RecordingContent) -> (Layout, Vec<(String, String)>) {
        out.layout.fit_titles(self.area())
    }

    /// What the default blueprint of `out` holds ([`BlueprintKey`]).
    pub fn blueprint_key(&self, out: &RecordingContent) -> BlueprintKey {
        BlueprintKey::of(self.fitted_layout(out).0, out)
    }

    /// Logs everything of `out` to `rec`: the text panel, the visuals, the blueprint.
    pub fn log(&self, rec: &RecordingStream, out: &RecordingContent) -> Result<()> {
        let (layout, shortened) = self.fitted_layout(out);
        let mut markdown = out.markdown.clone();
        if !shortened.is_empty() {
            let list: Vec<String> = shortened
                .iter()
                .map(|(short, full)| format!("{short} {full}"))
                .collect();
            markdown.push_str(&format!(
                "\n\nTab titles shortened to fit the window: {}.\n",
                list.join("; ")
            ));
        }
        // Tables wider than the text panel are written as lists (the panel would cut them).
        if let Some((width, _)) = layout.view_size("/scene", self.area()) {
            markdown = crate::markdown_tables::fit_tables(
                &markdown,
                width - crate::markdown_tables::PANEL_MARGIN,
            );
        }
        rec.log_static("scene", &rerun_sdk::TextDocument::from_markdown(markdown))
            .or_rerun()?;
        // The scene's numbers as `report --json` prints them, for `flexmodes diff` and for a
        // user inspecting a saved recording (no view shows it).
        rec.log_static(
            super::REPORT_ENTITY,
            &rerun_sdk::TextDocument::new(out.report.to_json().to_string()),
        )
        .or_rerun()?;
        let up = if out.y_up {
            rerun_sdk::ViewCoordinates::RIGHT_HAND_Y_UP()
        } else {
            rerun_sdk::ViewCoordinates::RIGHT_HAND_Z_UP()
        };
        // Planar bodies (the beam in the x-y plane) are drawn in 2D views, which frame their
        // contents exactly; solids in 3D views with their up axis.
        let planar = out.y_up;
        if !planar {
            for origin in layout.spatial_origins() {
                rec.log_static(origin.as_str(), &up).or_rerun()?;
            }
        }
        for v in &out.visuals {
            log_visual(rec, v, planar)?;
        }
        // Each 3D view starts with a camera that frames what it shows.
        let eye_for = |origin: &str, aspect: f64| {
            Bounds::of(origin, &out.visuals).map(|b| Eye::framing(&b, aspect))
        };
        let bounds_for = |origin: &str| Bounds::of(origin, &out.visuals);
        let series_range_for = |origin: &str| super::eye::series_range(origin, &out.visuals);
        send_blueprint(
            rec,
            &layout,
            &eye_for,
            &bounds_for,
            &series_range_for,
            &BlueprintParameters {
                planar,
                timeline: out.timeline.as_deref(),
                make_active: !self.default_blueprint_only,
                viewport: self.area(),
            },
        )?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::Visual;
    use crate::report::Report;

    fn content(visuals: Vec<Visual>) -> RecordingContent {
        RecordingContent {
            report: Report::new("test"),
            markdown: String::new(),
            visuals,
            layout: Layout::Tabs(Vec::new()),
            timeline: Some("sim_time".into()),
            y_up: false,
        }
    }

    #[test]
    fn frame_axes_of_mismatched_lengths_are_a_named_error_and_no_file() {
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let visual = |origins: usize, triads: usize| Visual::FrameAxes {
            path: "world/body/frame/mean".into(),
            times: vec![0.0, 0.1, 0.2],
            origins: vec![[0.0; 3]; origins],
            axes: vec![axes; triads],
            length: 1.0,
        };
        let dir = std::env::temp_dir().join(format!("flexmodes-axes-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("axes.rrd");
        for (origins, triads) in [(2, 3), (3, 4)] {
            let err = Recorder::default()
                .save(&content(vec![visual(origins, triads)]), &file)
                .unwrap_err();
            assert!(
                matches!(
                    err,
                    Error::MismatchedSeries { expected: 3, found, .. }
                        if found == if origins != 3 { origins } else { triads }
                ),
                "{err}"
            );
            assert!(err.to_string().contains("world/body/frame/mean"), "{err}");
            assert!(!file.exists());
        }
        Recorder::default()
            .save(&content(vec![visual(3, 3)]), &file)
            .unwrap();
        assert!(file.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
