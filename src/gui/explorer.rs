//! The explorer's state and side panel, without the viewer (so tests can drive it).

use std::{
    sync::Arc,
    time::{Duration, Instant},
};

use rerun::external::egui;

use crate::scenes::{self, SceneInfo};

use super::{
    Change, Command, Computed, Controls, ExplorerError, Worker, report_view::table_ui,
    viewer_handoff::HandoffState,
};
use crate::body_file::{BodyHandle, ImportedBody};

/// Controls, the worker, the last good recording and what went wrong.
pub struct Explorer {
    /// What the user chose (persisted).
    pub controls: Controls,
    pub(super) worker: Worker,
    generation: u64,
    /// When the running request started, if one runs.
    pub computing_since: Option<Instant>,
    /// The last good result, kept on screen when a later request fails.
    pub current: Option<Computed>,
    /// The last failure, if the last request or command failed.
    pub error: Option<ExplorerError>,
    /// From request to result on the UI thread, per finished request (switch latency), newest
    /// last.
    pub latencies: Vec<Duration>,
    /// Per successful request: running the scene and building its recording's messages, s.
    pub phase_times: Vec<(f64, f64)>,
    /// A one-line status (saved file, ...).
    pub status: String,
    /// Where "save" writes.
    pub save_path: String,
    fresh: bool,
    /// What the viewer does with the newest result (taken in while the previous one stays
    /// on screen); set by the window each frame.
    pub viewer_state: HandoffState,
    /// The report of the recording the viewer shows, once the window said so (see
    /// [`Self::shown`]); the panel's table follows it, not the newest result.
    on_screen: Option<crate::report::Report>,
    /// The body file of the `modes` scene as loaded, with the text it was loaded from.
    body: Option<(String, BodyHandle)>,
    /// Text being typed into the panel, not yet applied (transient).
    pub edits: Edits,
}

/// Text fields as typed, applied to the controls by a command when the user presses Enter or a
/// button; set back to the controls after every applied command.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Edits {
    /// The body file field.
    pub body: String,
    /// The boundary field.
    pub boundary: String,
}

impl Edits {
    fn of(controls: &Controls) -> Self {
        Self {
            body: controls.body.clone().unwrap_or_default(),
            boundary: controls.boundary.clone(),
        }
    }
}

impl Explorer {
    /// Starts with `controls` and requests the first computation.
    pub fn new(controls: Controls) -> Self {
        let save_path = controls.file_name();
        let mut e = Self {
            edits: Edits::of(&controls),
            controls,
            worker: Worker::new(),
            generation: 0,
            computing_since: None,
            current: None,
            error: None,
            latencies: Vec::new(),
            phase_times: Vec::new(),
            status: String::new(),
            save_path,
            fresh: false,
            viewer_state: HandoffState::Idle,
            on_screen: None,
            body: None,
        };
        e.request();
        e
    }

    /// Recomputes with the current controls (superseding a running request).
    pub fn request(&mut self) {
        let options = self
            .loaded_body()
            .and_then(|body| self.controls.options_with(body.as_ref()));
        match options {
            Ok(options) => {
                self.generation += 1;
                self.worker
                    .submit(self.generation, self.controls.scene, options);
                self.computing_since = Some(Instant::now());
            }
            Err(e) => self.error = Some(ExplorerError::Settings(Arc::new(e))),
        }
    }

    /// The body file of the `modes` scene, loaded (and checked) when its name changed; `None`
    /// for other scenes.
    pub(super) fn loaded_body(&mut self) -> crate::Result<Option<BodyHandle>> {
        if !self.controls.takes_body() {
            return Ok(None);
        }
        let name = self
            .controls
            .body
            .clone()
            .unwrap_or_else(|| scenes::body_modes::DEFAULT_BODY.to_string());
        if let Some((loaded, handle)) = &self.body
            && *loaded == name
        {
            return Ok(Some(handle.clone()));
        }
        let handle = BodyHandle(std::sync::Arc::new(ImportedBody::load(&name)?));
        self.body = Some((name, handle.clone()));
        Ok(Some(handle))
    }

    /// Node sets of the loaded body file, for the boundary menu.
    pub fn node_sets(&self) -> Vec<(String, usize)> {
        match &self.body {
            Some((_, b)) if self.controls.takes_body() => b
                .node_sets
                .iter()
                .map(|(k, v)| (k.clone(), v.len()))
                .collect(),
            _ => Vec::new(),
        }
    }

    /// Whether the loaded body file gives a preloaded stiffness (`[preload]`): the dynamic
    /// stiffening of its spin.
    pub fn body_has_preload(&self) -> bool {
        matches!(&self.body, Some((_, b)) if self.controls.takes_body() && b.preload.is_some())
    }

    /// The node set that is the loaded body's default interface, if one is.
    pub fn default_interface_set(&self) -> Option<String> {
        let (_, body) = self.body.as_ref()?;
        let nodes = body.default_interface_nodes().ok()?;
        self.node_sets()
            .into_iter()
            .map(|(name, _)| name)
            .find(|name| body.node_sets.get(name).map(Vec::as_slice) == Some(nodes))
    }

    /// Whether a request is running.
    /// Repaints `ctx` as soon as a result is ready (the switch latency would otherwise include
    /// up to one scheduled frame).
    pub fn wake(&self, ctx: &egui::Context) {
        self.worker.wake(ctx);
    }

    pub fn is_computing(&self) -> bool {
        self.computing_since.is_some()
    }

    /// Takes finished results; returns true when something changed.
    pub fn poll(&mut self) -> bool {
        let mut changed = false;
        while let Some(f) = self.worker.poll() {
            if f.generation != self.generation {
                continue; // superseded
            }
            // From the click to the result on the UI thread (queueing and the worker's
            // computation and encoding included).
            let since = self.computing_since.take();
            self.latencies
                .push(since.map_or(f.elapsed, |s| s.elapsed().max(f.elapsed)));
            match f.result {
                Ok(c) => {
                    self.anticipate();
                    self.phase_times.push((c.compute_s, c.messages_s));
                    self.current = Some(c);
                    self.error = None;
                    self.fresh = true;
                }
                Err(e) => self.error = Some(e),
            }
            changed = true;
        }
        changed
    }

    /// The window's viewer now shows the newest result.
    pub fn shown(&mut self) {
        self.on_screen = self.current.as_ref().map(|c| c.report.clone());
    }

    /// Bytes the kept time integrations weigh.
    pub fn cached_bytes(&self) -> usize {
        self.worker.cached_bytes()
    }

    /// The most the kept time integrations may weigh, bytes.
    pub fn cache_budget(&self) -> usize {
        self.worker.cache_budget()
    }

    /// Anticipated requests that ran to their end, and the cache's entries.
    pub fn anticipation_counts(&self) -> (u64, usize) {
        (self.worker.anticipated(), self.worker.cached())
    }

    /// The new recording to show, once per successful computation.
    pub fn take_fresh(&mut self) -> Option<&Computed> {
        if std::mem::take(&mut self.fresh) {
            self.current.as_ref()
        } else {
            None
        }
    }

    /// Applies the panel's commands.
    pub fn apply(&mut self, commands: Vec<Command>) {
        let any = !commands.is_empty();
        for c in commands {
            match c {
                Command::SelectScene(id) => {
                    self.controls = Controls::for_scene(id);
                    self.save_path = self.controls.file_name();
                    self.request();
                }
                Command::Set(change) => {
                    // The proposed file name follows the recording unless the user typed one.
                    let proposed = self.save_path == self.controls.file_name();
                    self.controls.change(change);
                    if proposed {
                        self.save_path = self.controls.file_name();
                    }
                    self.request();
                }
                Command::ResetBoundary => {
                    self.controls.boundary = self.controls.default_boundary();
                    self.request();
                }
                Command::Save(path) => match &self.current {
                    Some(c) => match c.rrd().and_then(|bytes| {
                        Ok(crate::atomic_file::write_bytes_atomically(&path, &bytes)?)
                    }) {
                        Ok(()) => self.status = format!("saved {}", path.display()),
                        Err(e) => {
                            self.error = Some(ExplorerError::Save {
                                path,
                                error: Arc::new(e),
                            })
                        }
                    },
                    None => self.status = "nothing to save yet".into(),
                },
            }
        }
        if any {
            self.edits = Edits::of(&self.controls);
        }
    }

    /// The side panel; returns what the user asked for.
    pub fn panel_ui(&mut self, ui: &mut egui::Ui) -> Vec<Command> {
        let mut out = Vec::new();
        ui.heading("flexmodes");
        let all = scenes::all();
        let mut scene = self.controls.scene;
        egui::ComboBox::from_label("scene")
            .selected_text(scene.as_str())
            .show_ui(ui, |ui| {
                for s in &all {
                    ui.selectable_value(&mut scene, s.id, s.id.as_str())
                        .on_hover_text(s.info.summary);
                }
            });
        if scene != self.controls.scene {
            out.push(Command::SelectScene(scene));
            return out;
        }
        let Some(info) = all
            .iter()
            .find(|s| s.id == self.controls.scene)
            .map(|s| s.info)
        else {
            return out;
        };
        ui.label(egui::RichText::new(info.summary).small());
        ui.separator();

        self.methods_ui(ui, &info, &mut out);
        self.body_ui(ui, &mut out);
        self.drive_ui(ui, &mut out);
        self.boundary_ui(ui, &info, &mut out);
        self.model_ui(ui, &info, &mut out);
        self.simulation_ui(ui, &info, &mut out);
        self.status_ui(ui);
        self.results_ui(ui, &mut out);
        out
    }

    /// The scene's method checkboxes and the kept modes.
    fn methods_ui(&mut self, ui: &mut egui::Ui, info: &SceneInfo, out: &mut Vec<Command>) {
        ui.label("methods");
        // A driven body is reduced only by the methods that hold its driven ring still.
        let driven = self.controls.takes_body() && self.controls.simulation.is_some();
        let offered = info
            .controls
            .methods
            .iter()
            .filter(|m| !driven || crate::models::DRIVEN_METHODS.contains(m));
        ui.horizontal_wrapped(|ui| {
            for m in offered {
                let mut on = self.controls.methods.contains(m);
                if ui
                    .checkbox(&mut on, m.id().to_uppercase())
                    .on_hover_text(m.name())
                    .changed()
                {
                    out.push(Command::Set(Change::Method(*m, on)));
                }
            }
        });
        if info.controls.modes.is_some() {
            ui.horizontal(|ui| {
                ui.label(format!("kept modes: {}", self.controls.modes));
                if ui.button("fewer modes").clicked() && self.controls.modes > 0 {
                    out.push(Command::Set(Change::Modes(self.controls.modes - 1)));
                }
                if ui.button("more modes").clicked() {
                    out.push(Command::Set(Change::Modes(self.controls.modes + 1)));
                }
            });
        }
    }

    /// A body scene's file, built-in bodies and interfaces (node sets, plain, rigid or averaged).
    fn body_ui(&mut self, ui: &mut egui::Ui, out: &mut Vec<Command>) {
        if self.controls.takes_body() {
            ui.horizontal(|ui| {
                ui.label("body file");
                let r = ui.add(
                    egui::TextEdit::singleline(&mut self.edits.body)
                        .hint_text(scenes::body_modes::DEFAULT_BODY)
                        .desired_width(170.0),
                );
                if r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                    out.push(Command::Set(Change::Body(self.edits.body.clone())));
                }
            });
            ui.horizontal_wrapped(|ui| {
                ui.label("built-in:");
                for name in crate::assets::builtin_bodies() {
                    let id = format!("builtin:{name}");
                    if ui
                        .selectable_label(self.controls.body.as_deref() == Some(id.as_str()), name)
                        .clicked()
                    {
                        out.push(Command::Set(Change::Body(id)));
                    }
                }
            });
            let sets = self.node_sets();
            // With no boundary typed, the body file's default interface is the one in use.
            let in_use = if self.controls.boundary.trim().is_empty() {
                self.default_interface_set().unwrap_or_default()
            } else {
                self.controls.boundary.clone()
            };
            // A driven body shows its drive instead (`simulation_ui`).
            if !sets.is_empty() && self.controls.simulation.is_none() {
                ui.horizontal_wrapped(|ui| {
                    ui.label("interface:");
                    for (name, count) in sets {
                        if ui
                            .selectable_label(in_use == name, &name)
                            .on_hover_text(format!("node set, {count} nodes"))
                            .clicked()
                        {
                            out.push(Command::Set(Change::Boundary(name)));
                        }
                    }
                });
                // The same sets tied rigidly to a 6-DOF master node (RBE2).
                ui.horizontal_wrapped(|ui| {
                    ui.label("rigid:");
                    for (name, count) in self.node_sets() {
                        let rigid = format!("rbe2:{name}");
                        if ui
                            .selectable_label(in_use == rigid, &rigid)
                            .on_hover_text(format!(
                                "{count} nodes tied to one 6-DOF master at their centroid"
                            ))
                            .clicked()
                        {
                            out.push(Command::Set(Change::Boundary(rigid)));
                        }
                    }
                });
                // The same sets averaged into a 6-DOF master node (RBE3): a place to load the
                // body that holds nothing (BH, MM and BT take it).
                ui.horizontal_wrapped(|ui| {
                    ui.label("averaged:");
                    for (name, count) in self.node_sets() {
                        let averaged = format!("rbe3:{name}");
                        if ui
                            .selectable_label(in_use == averaged, &averaged)
                            .on_hover_text(format!(
                                "{count} nodes averaged into one 6-DOF master at their \
                                 centroid; adds no stiffness (BH, MM, BT)"
                            ))
                            .clicked()
                        {
                            out.push(Command::Set(Change::Boundary(averaged)));
                        }
                    }
                });
            }
        }
    }

    /// The boundary nodes typed, applied or reset.
    fn boundary_ui(&mut self, ui: &mut egui::Ui, info: &SceneInfo, out: &mut Vec<Command>) {
        let driven = self.controls.simulation.is_some();
        if !info.controls.boundary.is_empty() || (self.controls.takes_body() && !driven) {
            ui.horizontal(|ui| {
                ui.label("boundary nodes");
                let r = ui
                    .add(egui::TextEdit::singleline(&mut self.edits.boundary).desired_width(110.0));
                if r.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter)) {
                    out.push(Command::Set(Change::Boundary(self.edits.boundary.clone())));
                }
            });
            ui.horizontal(|ui| {
                if ui.button("apply boundary").clicked() {
                    out.push(Command::Set(Change::Boundary(self.edits.boundary.clone())));
                }
                if ui.button("reset boundary").clicked() {
                    out.push(Command::ResetBoundary);
                }
            });
        }
    }

    /// What is computing, the last error and the last update's latency.
    fn status_ui(&mut self, ui: &mut egui::Ui) {
        if let Some(since) = self.computing_since {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label(format!("computing… {:.1} s", since.elapsed().as_secs_f64()));
            });
            if let Some(p) = self.worker.phase() {
                ui.label(format!(
                    "phase {}: {} ({:.1} s)",
                    p.number, p.name, p.elapsed_s
                ));
            }
            if let Some(r) = self.worker.progress() {
                let fraction = (r.time / r.end_time).clamp(0.0, 1.0) as f32;
                ui.add(egui::ProgressBar::new(fraction).text(format!(
                    "simulation {}: t = {:.2} of {:.2} s",
                    r.simulations, r.time, r.end_time
                )));
            }
        }
        if let Some(e) = &self.error {
            ui.colored_label(egui::Color32::from_rgb(230, 90, 80), format!("error: {e}"));
            if self.current.is_some() {
                ui.label("the last good recording stays on screen");
            }
        }
        if let Some(l) = self.latencies.last() {
            // What the kept integrations weigh: a refined slab's unreduced run is ~200 MB.
            let kept = self.worker.cached();
            let text = if kept > 0 {
                format!(
                    "last update took {:.2} s · {kept} integration(s) kept, {:.1} MB",
                    l.as_secs_f64(),
                    self.worker.cached_bytes() as f64 / 1e6
                )
            } else {
                format!("last update took {:.2} s", l.as_secs_f64())
            };
            ui.label(egui::RichText::new(text).small());
        }
    }

    /// The results table of the recording on screen and the save field.
    fn results_ui(&mut self, ui: &mut egui::Ui, out: &mut Vec<Command>) {
        // The table of the recording on screen: the viewer may still show the previous one.
        if let Some(report) = self
            .on_screen
            .as_ref()
            .or(self.current.as_ref().map(|c| &c.report))
        {
            ui.separator();
            ui.strong(format!("results: {}", report.scene));
            egui::ScrollArea::both().max_height(320.0).show(ui, |ui| {
                table_ui(ui, report);
            });
        }
        ui.separator();
        ui.horizontal(|ui| {
            ui.add(egui::TextEdit::singleline(&mut self.save_path).desired_width(140.0));
            if ui.button("save .rrd").clicked() {
                out.push(Command::Save(self.save_path.clone().into()));
            }
        });
        if !self.status.is_empty() {
            ui.label(egui::RichText::new(&self.status).small());
        }
    }
}
