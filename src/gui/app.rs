//! The native window: the explorer's panel on the left, the Rerun viewer in the rest.

use std::path::{Path, PathBuf};

use rerun::external::{
    eframe, egui,
    re_log_channel::{self, LogSource},
    re_log_encoding::DecoderApp,
    re_viewer,
};

use super::{
    Controls, Explorer, SimulationControls,
    capture::{Capture, FrameSeries},
    viewer_handoff::{HandoffState, Offer, ViewerHandoff},
};
use crate::{Error, Result, scenes::SceneId};

/// Window options of [`run`].
#[derive(Debug, Clone)]
pub struct ViewerOptions {
    /// Save a screenshot here once the first recording is shown (after `toggle`, the last),
    /// then quit.
    pub screenshot: Option<PathBuf>,
    /// Inner window size in points.
    pub window_size: Option<[f32; 2]>,
    /// The light (`true`) or dark theme; `None`: the viewer's own choice.
    pub light_theme: Option<bool>,
    /// Once the first recording shows, toggle this method (as a user would) and recompute;
    /// [`MORE_MODES`] or [`FEWER_MODES`] presses that button instead.
    pub toggle: Option<String>,
    /// How many times to toggle `toggle` (on, off, on, …), one recomputation each; the
    /// screenshot shows the last. 0 counts as 1.
    pub repeat: u32,
    /// How long to look at each recording before the next toggle.
    pub pause: std::time::Duration,
    /// Screenshots at fixed intervals after each toggle.
    pub frames: Option<FrameSeries>,
    /// Switch in one step once the new recording is in (see [`ViewerHandoff`]); `false`
    /// shows it as it arrives.
    pub atomic: bool,
}

impl Default for ViewerOptions {
    fn default() -> Self {
        Self {
            screenshot: None,
            window_size: None,
            light_theme: None,
            toggle: None,
            repeat: 0,
            pause: std::time::Duration::ZERO,
            frames: None,
            atomic: true,
        }
    }
}

/// [`ViewerOptions::toggle`] that presses "more modes".
pub const MORE_MODES: &str = "more-modes";
/// [`ViewerOptions::toggle`] that presses "fewer modes".
pub const FEWER_MODES: &str = "fewer-modes";

const STORAGE_KEY: &str = "flexmodes-controls";

/// The explorer's panel width at start, points.
const PANEL_WIDTH: f32 = 330.0;

/// The viewer's part of a 1 280 × 800 explorer window (the panel, the viewer's top bar and
/// its collapsed time panel taken away), points: what each scene's layout must fit.
pub const VIEWER_AREA: (f64, f64) = (1280.0 - PANEL_WIDTH as f64, 730.0);

struct FlexmodesApp {
    explorer: Option<Explorer>,
    viewer: re_viewer::App,
    handoff: ViewerHandoff,
    capture: Option<Capture>,
    /// A saved recording's messages were sent and the capture is not told yet (a file is
    /// sent whole, outside the handoff's phases; the capture's settling frames then let the
    /// viewer take it in).
    file_sent: bool,
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
        if let Some(c) = &mut self.capture {
            let idle = self.handoff.state() == HandoffState::Idle
                && self.explorer.as_ref().is_none_or(|e| !e.is_computing());
            if c.step(ctx, idle) {
                if let Some(e) = &self.explorer {
                    c.report(e);
                }
                ctx.send_viewport_cmd(egui::ViewportCommand::Close);
            }
        }
        if let Some(mut explorer) = self.explorer.take() {
            explorer.wake(ctx);
            explorer.poll();
            if let Some(offer) = explorer.take_fresh().map(|c| Offer {
                messages: c.messages.clone(),
                blueprint: c.blueprint.clone(),
            }) {
                let start = std::time::Instant::now();
                self.handoff.offer(ctx, offer);
                if let Some(c) = &mut self.capture {
                    c.handoffs.push(start.elapsed());
                }
            }
            if self.handoff.step(ctx) {
                explorer.shown();
                if let Some(c) = &mut self.capture {
                    c.on_shown(ctx);
                }
            }
            explorer.viewer_state = self.handoff.state();
            if let Some(c) = &mut self.capture {
                c.toggle_step(ctx, &mut explorer);
            }
            if explorer.is_computing() || explorer.viewer_state != HandoffState::Idle {
                // Keep the spinner turning; the worker's result is polled next frame.
                ctx.request_repaint_after(std::time::Duration::from_millis(50));
            }
            self.explorer = Some(explorer);
        } else {
            self.handoff.step(ctx);
            // A saved recording (`view FILE --screenshot`): the capture told once it is sent,
            // then it waits its settling frames; before, nothing told it and it waited for ever.
            if std::mem::take(&mut self.file_sent)
                && let Some(c) = &mut self.capture
            {
                c.on_shown(ctx);
            }
        }
        eframe::App::logic(&mut self.viewer, ctx, frame);
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        if let Some(explorer) = &mut self.explorer {
            let commands = egui::Panel::left("flexmodes-panel")
                .default_size(PANEL_WIDTH)
                .show(ui, |ui| {
                    egui::ScrollArea::vertical()
                        .show(ui, |ui| explorer.panel_ui(ui))
                        .inner
                })
                .inner;
            explorer.apply(commands);
        }
        // What is left of the window after the panel is the viewer's.
        let viewer_rect = ui.available_rect_before_wrap();
        eframe::App::ui(&mut self.viewer, ui, frame);
        self.handoff.paint_cover(ui.ctx(), viewer_rect);
        if let Some(explorer) = &self.explorer {
            explorer.updating_badge(ui.ctx());
        }
    }
}

/// Opens the explorer on `scene` (default `beam-modes`), or the viewer on a saved recording.
pub fn run(scene: Option<SceneId>, file: Option<&Path>, opts: ViewerOptions) -> Result<()> {
    run_with_body(scene, None, None, file, opts)
}

/// [`run`], or the explorer on the `modes` scene with the body file `body` (loaded and checked
/// first, so a bad file fails before a window opens), driven as `simulate` says when given.
pub fn run_with_body(
    scene: Option<SceneId>,
    body: Option<&str>,
    simulate: Option<SimulationControls>,
    file: Option<&Path>,
    opts: ViewerOptions,
) -> Result<()> {
    let file_bytes = match file {
        Some(p) => Some(std::fs::read(p).map_err(|source| Error::io(p, source))?),
        None => None,
    };
    let explicit_scene = scene.is_some() || body.is_some();
    let initial = initial_controls(file_bytes.is_some(), scene, body, simulate)?;
    let capture = capture_of(&opts);
    let atomic = opts.atomic;
    let light_theme = opts.light_theme;
    let runtime =
        tokio::runtime::Runtime::new().map_err(|e| Error::rerun("desktop app's runtime", e))?;
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
            if let Some(light) = light_theme {
                cc.egui_ctx.options_mut(|o| {
                    o.theme_preference = if light {
                        egui::ThemePreference::Light
                    } else {
                        egui::ThemePreference::Dark
                    }
                });
            }
            let (tx, rx) = re_log_channel::log_channel(LogSource::Sdk);
            viewer.add_log_receiver(rx);
            // Restore the last session's controls when they still name a scene.
            let restored = cc
                .storage
                .and_then(|s| s.get_string(STORAGE_KEY))
                .and_then(|t| serde_json::from_str::<Controls>(&t).ok());
            let controls = match (initial, restored) {
                (Some(_), Some(r)) if !explicit_scene => Some(r),
                (i, _) => i,
            };
            let handoff = ViewerHandoff::new(tx, viewer.command_sender.clone(), atomic);
            let mut app = FlexmodesApp {
                explorer: controls.map(Explorer::new),
                viewer,
                handoff,
                capture,
                file_sent: false,
            };
            if let Some(bytes) = &file_bytes {
                app.handoff.show_file(
                    DecoderApp::decode_lazy(bytes.as_slice())
                        .flatten()
                        .collect(),
                );
                app.file_sent = true;
            }
            Ok(Box::new(app))
        }),
        None,
    )
    .map_err(|e| Error::rerun("desktop app", e))?;
    drop(runtime);
    Ok(())
}

/// The controls the window opens with: none for a recording file, the body's for `body`
/// (loaded, and the drive and motion of `simulate` checked, before a window opens), else the
/// scene's.
fn initial_controls(
    file: bool,
    scene: Option<SceneId>,
    body: Option<&str>,
    simulate: Option<SimulationControls>,
) -> Result<Option<Controls>> {
    Ok(match (file, scene, body) {
        (true, _, _) => None,
        (false, _, Some(b)) => {
            let loaded = crate::body_file::ImportedBody::load(b)?;
            let mut controls = Controls::for_body(b)?;
            if let Some(s) = &simulate {
                // The drive and its motion checked before a window opens.
                s.simulation()?;
                loaded.boundary(std::slice::from_ref(&s.drive))?;
            }
            controls.change(super::Change::Simulation(simulate));
            Some(controls)
        }
        (false, s, None) => Some(Controls::for_scene(s.unwrap_or(SceneId::BeamModes))),
    })
}

/// The screenshot capture `opts` asks for, with its toggles.
fn capture_of(opts: &ViewerOptions) -> Option<Capture> {
    let toggles = if opts.toggle.is_some() {
        opts.repeat.max(1)
    } else {
        0
    };
    opts.screenshot.clone().map(|path| {
        Capture::new(
            path,
            opts.toggle.clone(),
            toggles,
            opts.pause,
            opts.frames.clone(),
        )
    })
}
