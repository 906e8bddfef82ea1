//! Scripted runs of the explorer (`gui --screenshot`): wait for the first recording, toggle
//! a method (or press a modes button) a number of times, take screenshots at fixed intervals
//! after each toggle, save the last view as PNG, print timings and memory, and quit.

use std::{
    path::PathBuf,
    time::{Duration, Instant},
};

use rerun::external::egui;

use super::{Explorer, FEWER_MODES, MORE_MODES};
use crate::linalg::resident_bytes;

/// Frames to let the viewer lay out a recording before the final screenshot.
const SETTLE_FRAMES: u32 = 30;

/// Screenshots taken at fixed intervals after each toggle.
#[derive(Debug, Clone)]
pub struct FrameSeries {
    /// Folder the frames go to (`switch-SS-FF.png`), created if missing.
    pub dir: PathBuf,
    /// Time between two frames.
    pub every: Duration,
    /// Frames per toggle; the first is taken at the toggle itself.
    pub count: u32,
}

/// What a scripted run does.
#[derive(Debug)]
pub(super) struct Capture {
    path: PathBuf,
    toggle: Option<String>,
    /// Toggles still to make; `wanted` recordings in all before the screenshot.
    toggles_left: u32,
    /// Time to wait after a recording shows before toggling.
    pause: Duration,
    /// When the next toggle is due.
    toggle_at: Option<Instant>,
    wanted: u32,
    shown: u32,
    settle: u32,
    requested: bool,
    frames: Option<FrameSeries>,
    /// Frame times still to take for the current toggle: (toggle number, frame number, due).
    frames_due: Vec<(u32, u32, Instant)>,
    /// Memory after each recording was shown.
    pub memory: Vec<MemorySample>,
    /// Time spent handing each new recording to the viewer, newest last.
    pub handoffs: Vec<Duration>,
    /// When the last toggle was made.
    toggled: Option<Instant>,
    /// From each toggle to the new recording shown (every message in the viewer).
    pub toggle_to_shown: Vec<Duration>,
}

/// Marks our screenshot requests apart from the viewer's own: the final one, or a frame of
/// a series.
#[derive(Debug, Clone)]
enum Shot {
    Final,
    Frame(PathBuf),
}

impl Capture {
    pub(super) fn new(
        path: PathBuf,
        toggle: Option<String>,
        toggles: u32,
        pause: Duration,
        frames: Option<FrameSeries>,
    ) -> Self {
        if let Some(f) = &frames
            && let Err(e) = std::fs::create_dir_all(&f.dir)
        {
            eprintln!("error: could not create {}: {e}", f.dir.display());
        }
        Self {
            path,
            toggle,
            toggles_left: toggles,
            pause,
            toggle_at: None,
            wanted: toggles + 1,
            shown: 0,
            settle: 0,
            requested: false,
            frames,
            frames_due: Vec::new(),
            memory: Vec::new(),
            handoffs: Vec::new(),
            toggled: None,
            toggle_to_shown: Vec::new(),
        }
    }

    /// A new recording became the one shown.
    pub(super) fn on_shown(&mut self, ctx: &egui::Context) {
        self.shown += 1;
        self.settle = 0;
        self.memory.push(MemorySample::now(ctx));
        if let Some(t) = self.toggled.take() {
            self.toggle_to_shown.push(t.elapsed());
        }
        if self.toggles_left > 0 {
            self.toggle_at = Some(Instant::now() + self.pause);
        }
    }

    /// Makes the toggle when due, requesting the frames of its series.
    pub(super) fn toggle_step(&mut self, ctx: &egui::Context, explorer: &mut Explorer) {
        let Some(due) = self.toggle_at else { return };
        let now = Instant::now();
        if now < due {
            ctx.request_repaint_after(due - now);
            return;
        }
        self.toggle_at = None;
        let Some(m) = self.toggle.clone() else { return };
        self.toggles_left -= 1;
        match m.as_str() {
            MORE_MODES => explorer.controls.modes += 1,
            FEWER_MODES => explorer.controls.modes = explorer.controls.modes.saturating_sub(1),
            id => match id.parse::<crate::reduction::Method>() {
                Ok(method) if explorer.controls.methods.contains(&method) => {
                    explorer.controls.methods.retain(|&shown| shown != method)
                }
                Ok(method) => explorer.controls.methods.push(method),
                // Nothing to toggle: the recording stays as it is.
                Err(_) => {}
            },
        }
        explorer.request();
        self.toggled = Some(now);
        if let Some(f) = &self.frames {
            let switch = self.shown;
            self.frames_due = (0..f.count)
                .map(|k| (switch, k, now + f.every * k))
                .collect();
        }
    }

    /// Requests the earliest frame that is due (one per frame drawn: frames due together
    /// are taken on successive frames).
    fn frame_step(&mut self, ctx: &egui::Context) {
        let Some(f) = &self.frames else { return };
        if self
            .frames_due
            .first()
            .is_some_and(|(_, _, t)| *t <= Instant::now())
        {
            let (switch, k, _) = self.frames_due.remove(0);
            let path = f.dir.join(format!("switch-{switch:02}-{k:02}.png"));
            ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::new(
                Shot::Frame(path),
            )));
        }
    }

    /// Saves screenshots that arrived; when the wanted recording has shown for a while and
    /// nothing is computing or loading, asks for the final one. Returns true once the final
    /// screenshot is saved (the run is over).
    pub(super) fn step(&mut self, ctx: &egui::Context, idle: bool) -> bool {
        let shots: Vec<(Shot, std::sync::Arc<egui::ColorImage>)> = ctx.input(|i| {
            i.raw
                .events
                .iter()
                .filter_map(|e| match e {
                    egui::Event::Screenshot {
                        image, user_data, ..
                    } => user_data
                        .data
                        .as_ref()
                        .and_then(|d| d.downcast_ref::<Shot>())
                        .map(|s| (s.clone(), image.clone())),
                    _ => None,
                })
                .collect()
        });
        let mut finished = false;
        for (shot, image) in shots {
            match shot {
                Shot::Final => {
                    save_png(&image, &self.path, true);
                    finished = true;
                }
                Shot::Frame(path) => {
                    // Encoding takes longer than a frame in a debug build: off the UI thread.
                    std::thread::spawn(move || save_png(&image, &path, false));
                }
            }
        }
        if finished {
            return true;
        }
        self.frame_step(ctx);
        let ready = self.shown >= self.wanted && idle && self.frames_due.is_empty();
        if ready && !self.requested {
            self.settle += 1;
            if self.settle >= SETTLE_FRAMES {
                self.requested = true;
                ctx.send_viewport_cmd(egui::ViewportCommand::Screenshot(egui::UserData::new(
                    Shot::Final,
                )));
            }
        }
        ctx.request_repaint();
        false
    }

    /// Prints what the run measured: update times, switch latency, memory.
    pub(super) fn report(&self, e: &Explorer) {
        // Click to result on the UI thread, plus handing it to the viewer.
        let total: Vec<f64> = e
            .latencies
            .iter()
            .zip(&self.handoffs)
            .map(|(a, b)| (*a + *b).as_secs_f64())
            .collect();
        let list = |v: &mut dyn Iterator<Item = f64>| {
            v.map(|d| format!("{d:.3}")).collect::<Vec<_>>().join(", ")
        };
        eprintln!(
            "update times (request to viewer), s: {}",
            list(&mut total.iter().copied())
        );
        eprintln!(
            "  of which handing to the viewer, s: {}",
            list(&mut self.handoffs.iter().map(Duration::as_secs_f64))
        );
        eprintln!(
            "from toggle to the new recording shown (all of it in the viewer), s: {}",
            list(&mut self.toggle_to_shown.iter().map(Duration::as_secs_f64))
        );
        let phases: Vec<String> = e
            .phase_times
            .iter()
            .map(|(c, m)| format!("{c:.3}/{m:.3}"))
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
                "  anticipated requests run to their end: {anticipated}; cache entries: {cached}"
            );
        }
        report_memory(&self.memory, e);
    }
}

/// Memory measured after a recording was shown.
#[derive(Debug, Clone, Copy)]
pub struct MemorySample {
    /// The process' resident set size, bytes (everything: our heap, the viewer's, the
    /// graphics driver's).
    pub resident: u64,
    /// Bytes live on the Rust heap (ours and the embedded viewer's), as counted by the
    /// accounting allocator the `flexmodes` binary installs; `None` where it is not installed
    /// (tests).
    pub heap: Option<u64>,
    /// Frames drawn so far.
    pub frames: u64,
}

impl MemorySample {
    /// Measures now.
    pub fn now(ctx: &egui::Context) -> Self {
        Self {
            resident: resident_bytes().unwrap_or(0),
            heap: rust_heap_bytes(),
            frames: ctx.cumulative_frame_nr(),
        }
    }
}

/// Bytes live on the Rust heap, if the binary counts them (see `main.rs`).
pub fn rust_heap_bytes() -> Option<u64> {
    rerun::external::re_viewer::external::re_memory::accounting_allocator::global_allocs()
        .map(|c| c.size as u64)
}

/// Prints the memory series of a scripted run and what it says: growth of the Rust heap
/// (data: our run cache, the viewer's stores and caches) apart from growth outside it (the
/// graphics driver's), per switch and per frame drawn.
fn report_memory(memory: &[MemorySample], e: &Explorer) {
    let mib = |b: f64| b / (1u64 << 20) as f64;
    let series = |f: &dyn Fn(&MemorySample) -> u64| {
        memory
            .iter()
            .map(|m| format!("{:.0}", mib(f(m) as f64)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    eprintln!(
        "resident memory after each recording shown, MiB: {}",
        series(&|m| m.resident)
    );
    if memory.iter().all(|m| m.heap.is_some()) {
        eprintln!(
            "Rust heap (ours and the viewer's) after each recording shown, MiB: {}",
            series(&|m| m.heap.unwrap_or(0))
        );
    }
    let (Some(first), Some(last)) = (memory.first(), memory.last()) else {
        return;
    };
    let peak = memory.iter().map(|m| m.resident).max().unwrap_or(0);
    let frames = last.frames.saturating_sub(first.frames);
    eprintln!(
        "resident memory, MiB: {:.0} after the first recording, {:.0} after the last \
         ({} shown, {frames} frames drawn between), peak {:.0}; growth {:.0} MiB; \
         run cache {:.1} of its {:.0} MiB bound",
        mib(first.resident as f64),
        mib(last.resident as f64),
        memory.len(),
        mib(peak as f64),
        mib(last.resident.saturating_sub(first.resident) as f64),
        mib(e.cached_bytes() as f64),
        mib(e.cache_budget() as f64),
    );
    if let (Some(h0), Some(h1)) = (first.heap, last.heap) {
        let peak_heap = memory.iter().filter_map(|m| m.heap).max().unwrap_or(0);
        let outside = |m: &MemorySample| m.resident as f64 - m.heap.unwrap_or(0) as f64;
        let grown_outside = mib(outside(last) - outside(first));
        eprintln!(
            "Rust heap, MiB: {:.0} after the first recording, {:.0} after the last, peak {:.0} \
             (growth {:+.1} MiB over {} switches); outside the Rust heap (graphics driver, \
             allocator slack) grew {grown_outside:.0} MiB, {:.2} MiB per frame drawn",
            mib(h0 as f64),
            mib(h1 as f64),
            mib(peak_heap as f64),
            mib(h1 as f64 - h0 as f64),
            memory.len() - 1,
            grown_outside / frames.max(1) as f64,
        );
    }
}

fn save_png(image: &egui::ColorImage, path: &std::path::Path, say: bool) {
    let [w, h] = image.size;
    let rgba: Vec<u8> = image.pixels.iter().flat_map(|p| p.to_array()).collect();
    let Some(img) = image::RgbaImage::from_raw(w as u32, h as u32, rgba) else {
        eprintln!("error: screenshot buffer has the wrong size");
        return;
    };
    // Encoded in memory, then written through the one atomic writer: a check reading the
    // folder never sees half a PNG.
    let mut png = std::io::Cursor::new(Vec::new());
    if let Err(e) = img.write_to(&mut png, image::ImageFormat::Png) {
        eprintln!("error: could not encode {}: {e}", path.display());
        return;
    }
    match crate::atomic_file::write_atomically(path, |f| f.write_all(png.get_ref())) {
        Ok(()) if say => eprintln!("screenshot saved to {}", path.display()),
        Ok(()) => {}
        Err(e) => eprintln!("error: could not save {}: {e}", path.display()),
    }
}
