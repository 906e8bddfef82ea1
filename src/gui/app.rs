//! The native window: the explorer's panel on the left, the Rerun viewer in the rest.

use std::path::{Path, PathBuf};

use re_viewer_context::{RecordingOrTable, SystemCommand, SystemCommandSender as _};
use rerun::external::{
    eframe, egui,
    re_log_channel::{self, LogSender, LogSource},
    re_log_encoding::DecoderApp,
    re_log_types::{LogMsg, StoreId},
    re_viewer::{self, external::re_viewer_context},
};

use super::{Controls, Explorer};
use crate::{Error, Result};

/// Window options of [`run`].
#[derive(Debug, Clone, Default)]
pub struct ViewerOptions {
    /// Save a screenshot here once the first recording is shown (after `toggle`, the second),
    /// then quit.
    pub screenshot: Option<PathBuf>,
    /// Inner window size in points.
    pub window_size: Option<[f32; 2]>,
    /// Once the first recording shows, toggle this method (as a user would) and recompute;
    /// [`MORE_MODES`] or [`FEWER_MODES`] presses that button instead.
    pub toggle: Option<String>,
    /// How many times to toggle `toggle` (on, off, on, …), one recomputation each; the
    /// screenshot shows the last. 0 counts as 1.
    pub repeat: u32,
    /// How long to look at each recording before the next toggle.
    pub pause: std::time::Duration,
}

/// [`ViewerOptions::toggle`] that presses "more modes".
pub const MORE_MODES: &str = "more-modes";
/// [`ViewerOptions::toggle`] that presses "fewer modes".
pub const FEWER_MODES: &str = "fewer-modes";

/// Frames to let the viewer ingest and lay out a recording before a screenshot.
const SETTLE_FRAMES: u32 = 30;

/// Scripted screenshot: waits for results, optionally toggles a method, then captures.
#[derive(Debug)]
struct Capture {
    path: PathBuf,
    toggle: Option<String>,
    /// Toggles still to make; `wanted` recordings in all before the screenshot.
    toggles_left: u32,
    /// Time to wait after a recording shows before toggling.
    pause: std::time::Duration,
    /// When the next toggle is due.
    toggle_at: Option<std::time::Instant>,
    wanted: u32,
    shown: u32,
    settle: u32,
    requested: bool,
}

const STORAGE_KEY: &str = "flexmodes-controls";

struct FlexmodesApp {
    explorer: Option<Explorer>,
    viewer: re_viewer::App,
    tx: LogSender,
    shown: Option<StoreId>,
    capture: Option<Capture>,
    /// Time spent handing each new recording to the viewer (decoding included), newest last.
    handoffs: Vec<std::time::Duration>,
}

impl FlexmodesApp {
    fn show_recording(&mut self, messages: Vec<LogMsg>) {
        let mut first: Option<StoreId> = None;
        for msg in messages {
            if let LogMsg::SetStoreInfo(info) = &msg
                && first.is_none()
                && info.info.store_id.is_recording()
            {
                first = Some(info.info.store_id.clone());
            }
            let _ = self.tx.send(msg.into());
        }
        // The new recording replaces the old one in memory; the layout (per application id)
        // stays as the user left it.
        if let Some(old) = self.shown.take() {
            self.viewer
                .command_sender
                .send_system(SystemCommand::CloseRecordingOrTable(
                    RecordingOrTable::Recording { store_id: old },
                ));
        }
        self.shown = first;
    }
}

impl eframe::App for FlexmodesApp {
    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if let Some(e) = &self.explorer
            && let Ok(text) = serde_json::to_string(&e.controls)
        {
            storage.set_string(STORAGE_KEY, text);
        }
        self.viewer.save(storage);
    }

    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        eframe::App::clear_color(&self.viewer, visuals)
    }

    fn logic(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        self.capture_step(ctx);
        if let Some(mut explorer) = self.explorer.take() {
            explorer.wake(ctx);
            explorer.poll();
            if let Some(messages) = explorer.take_fresh().map(|c| c.messages.clone()) {
                let start = std::time::Instant::now();
                self.show_recording(messages);
                self.handoffs.push(start.elapsed());
                if let Some(c) = &mut self.capture {
                    c.shown += 1;
                    c.settle = 0;
                    if c.toggles_left > 0 {
                        c.toggle_at = Some(std::time::Instant::now() + c.pause);
                    }
                }
            }
            if let Some(c) = &mut self.capture
                && let Some(due) = c.toggle_at
            {
                if std::time::Instant::now() >= due {
                    c.toggle_at = None;
                    if let Some(m) = c.toggle.clone() {
                        c.toggles_left -= 1;
                        match m.as_str() {
                            MORE_MODES => explorer.controls.modes += 1,
                            FEWER_MODES => {
                                explorer.controls.modes = explorer.controls.modes.saturating_sub(1)
                            }
                            _ if explorer.controls.methods.contains(&m) => {
                                explorer.controls.methods.retain(|id| *id != m)
                            }
                            _ => explorer.controls.methods.push(m),
                        }
                        explorer.request();
                    }
                } else {
                    ctx.request_repaint_after(due - std::time::Instant::now());
                }
            }
            if explorer.is_computing() {
                // Keep the spinner turning; the worker's result is polled next frame.
                ctx.request_repaint_after(std::time::Duration::from_millis(50));
            }
            self.explorer = Some(explorer);
        }
        eframe::App::logic(&mut self.viewer, ctx, frame);
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if let Some(explorer) = &mut self.explorer {
            let commands = egui::Panel::left("flexmodes-panel")
                .default_size(330.0)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical()
                        .show(ui, |ui| explorer.panel_ui(ui))
                        .inner
                })
                .inner;
            explorer.apply(commands);
        }
        eframe::App::ui(&mut self.viewer, ui, frame);
    }
}

impl FlexmodesApp {
    /// Drives `--screenshot`: once the wanted recording has shown for a while (and nothing is
    /// computing), asks egui for a screenshot, saves it as PNG and closes the window.
    fn capture_step(&mut self, ctx: &egui::Context) {
        let Some(c) = &mut self.capture else { return };
        let image = ctx.input(|i| {
            i.raw.events.iter().find_map(|e| match e {
                egui::Event::Screenshot {
                    image, user_data, ..
                } if user_data
                    .data
                    .as_ref()
                    .is_some_and(|d| d.downcast_ref::<FlexmodesShot>().is_some()) =>
                {
                    Some(image.clone())
                }
                _ => None,
            })
        });
        if let Some(image) = image {
            let [w, h] = image.size;
            let rgba: Vec<u8> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
            match image::RgbaImage::from_raw(w as u32, h as u32, rgba) {
                Some(img) => match img.save(&c.path) {
                    Ok(()) => eprintln!("screenshot saved to {}", c.path.display()),
                    Err(e) => eprintln!("error: could not save {}: {e}", c.path.display()),
                },
                None => eprintln!("error: screenshot buffer has the wrong size"),
            }
            if let Some(e) = &self.explorer {
                // Click to result on the UI thread, plus handing it to the viewer.
                let total: Vec<f64> = e
                    .latencies
                    .iter()
                    .zip(&self.handoffs)
                    .map(|(a, b)| (*a + *b).as_secs_f64())
                    .collect();
                let l: Vec<String> = total.iter().map(|d| format!("{d:.3}")).collect();
                eprintln!("update times (request to viewer), s: {}", l.join(", "));
                let h: Vec<String> = self
                    .handoffs
                    .iter()
                    .map(|d| format!("{:.3}", d.as_secs_f64()))
                    .collect();
                eprintln!("  of which handing to the viewer, s: {}", h.join(", "));
                let phases: Vec<String> = e
                    .phase_times
                    .iter()
                    .map(|(c, e)| format!("{c:.3}/{e:.3}"))
                    .collect();
                eprintln!(
                    "  of which running the scene / building the recording's messages, s: {}",
                    phases.join(", ")
                );
                // The first is the scene's opening; the rest are switches.
                let mut switches: Vec<f64> = total.iter().skip(1).copied().collect();
                if !switches.is_empty() {
                    switches.sort_by(f64::total_cmp);
                    let n = switches.len();
                    let median = if n % 2 == 1 {
                        switches[n / 2]
                    } else {
                        0.5 * (switches[n / 2 - 1] + switches[n / 2])
                    };
                    eprintln!("switch latency, s: median {median:.3} over {n}");
                    let (anticipated, cached) = e.anticipation_counts();
                    eprintln!(
                        "  anticipated requests run to their end: {anticipated}; cache entries: \
                         {cached}"
                    );
                }
            }
            ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            return;
        }
        let idle = self.explorer.as_ref().is_none_or(|e| !e.is_computing());
        let ready = (self.explorer.is_none() || c.shown >= c.wanted) && idle;
        if ready && !c.requested {
            c.settle += 1;
            if c.settle >= SETTLE_FRAMES {
                c.requested = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::new(
                    FlexmodesShot,
                )));
            }
        }
        ctx.request_repaint();
    }
}

/// Marks our screenshot requests apart from the viewer's own.
#[derive(Debug, Clone, Copy)]
struct FlexmodesShot;

/// Opens the explorer on `scene` (default `beam-modes`), or the viewer on a saved recording.
pub fn run(scene: Option<&str>, file: Option<&Path>, opts: ViewerOptions) -> Result<()> {
    run_with_body(scene, None, file, opts)
}

/// [`run`], or the explorer on the `modes` scene with the body file `body` (loaded and checked
/// first, so a bad file fails before a window opens).
pub fn run_with_body(
    scene: Option<&str>,
    body: Option<&str>,
    file: Option<&Path>,
    opts: ViewerOptions,
) -> Result<()> {
    let gui_error = |e: String| Error::Rerun(format!("desktop app: {e}"));
    let file_bytes = match file {
        Some(p) => Some(std::fs::read(p).map_err(|source| Error::Io {
            path: p.display().to_string(),
            source,
        })?),
        None => None,
    };
    let explicit_scene = scene.is_some() || body.is_some();
    let initial = match (&file_bytes, scene, body) {
        (Some(_), _, _) => None,
        (None, _, Some(b)) => {
            crate::body_file::ImportedBody::load(b)?;
            Some(Controls::for_body(b)?)
        }
        (None, s, None) => Some(Controls::for_scene(s.unwrap_or("beam-modes"))?),
    };
    let toggles = if opts.toggle.is_some() {
        opts.repeat.max(1)
    } else {
        0
    };
    let capture = opts.screenshot.clone().map(|path| Capture {
        path,
        toggle: opts.toggle.clone(),
        toggles_left: toggles,
        pause: opts.pause,
        toggle_at: None,
        wanted: toggles + 1,
        shown: 0,
        settle: 0,
        requested: false,
    });
    let runtime = tokio::runtime::Runtime::new().map_err(|e| gui_error(e.to_string()))?;
    let handle = runtime.handle().clone();
    let main_thread_token = re_viewer::MainThreadToken::i_promise_i_am_on_the_main_thread();
    let startup = re_viewer::StartupOptions {
        resolution_in_points: opts.window_size,
        hide_welcome_screen: true,
        expect_data_soon: Some(true),
        ..Default::default()
    };
    re_viewer::run_native_app(
        main_thread_token,
        Box::new(move |cc| {
            re_viewer::customize_eframe_and_setup_renderer(cc)?;
            let mut viewer = re_viewer::App::new(
                main_thread_token,
                re_viewer::build_info(),
                re_viewer::AppEnvironment::Custom("flexmodes".into()),
                startup,
                cc,
                None,
                re_viewer::AsyncRuntimeHandle::new_native(handle),
            );
            let (tx, rx) = re_log_channel::log_channel(LogSource::Sdk);
            viewer.add_log_receiver(rx);
            // Restore the last session's controls when they still name a scene.
            let restored = cc
                .storage
                .and_then(|s| s.get_string(STORAGE_KEY))
                .and_then(|t| serde_json::from_str::<Controls>(&t).ok())
                .filter(|c| crate::scenes::find(&c.scene).is_ok());
            let controls = match (initial, restored) {
                (Some(_), Some(r)) if !explicit_scene => Some(r),
                (i, _) => i,
            };
            let mut app = FlexmodesApp {
                explorer: controls.map(Explorer::new),
                viewer,
                tx,
                shown: None,
                capture,
                handoffs: Vec::new(),
            };
            if let Some(bytes) = &file_bytes {
                app.show_recording(
                    DecoderApp::decode_lazy(bytes.as_slice())
                        .flatten()
                        .collect(),
                );
            }
            Ok(Box::new(app))
        }),
        None,
    )
    .map_err(|e| gui_error(e.to_string()))?;
    drop(runtime);
    Ok(())
}
