//! Scene computation off the UI thread; a newer request supersedes older ones and stops a
//! running time integration at its next output step. While the user looks at a result, a
//! second thread at low priority runs the requests the user is likely to make next (one mode
//! more or fewer, a method ticked) so their integrations are in the cache when asked for.

use std::{
    sync::{
        Arc,
        atomic::{AtomicU64, Ordering},
        mpsc::{Receiver, Sender, channel},
    },
    time::{Duration, Instant},
};

use rerun::external::{egui, re_log_types::LogMsg};

use super::ExplorerError;
use crate::{
    Progress, ProgressReading,
    record::Recorder,
    report::Report,
    scenes::{self, RunCache, SceneId, SceneOptions},
};

/// A finished computation: the numbers, the panel text and the recording.
#[derive(Debug, Clone)]
pub struct Computed {
    /// Scene id.
    pub scene: SceneId,
    /// The numeric report.
    pub report: Report,
    /// Entity paths logged.
    pub entity_paths: Vec<String>,
    /// The views' layout and what each starts showing: what its default blueprint holds.
    pub blueprint: crate::record::BlueprintKey,
    /// The recording's messages, as the viewer takes them (encoded only to be saved).
    pub messages: Vec<LogMsg>,
    /// Running the scene, s.
    pub compute_s: f64,
    /// Building the recording's messages, s.
    pub messages_s: f64,
}

impl Computed {
    /// The recording as the bytes of an `.rrd` file.
    pub fn rrd(&self) -> crate::Result<Vec<u8>> {
        crate::record::encode_messages(&self.messages)
    }
}

/// The outcome of one request.
#[derive(Debug)]
pub struct Finished {
    /// The request's generation.
    pub generation: u64,
    /// The result, or what failed.
    pub result: Result<Computed, ExplorerError>,
    /// How long the computation took.
    pub elapsed: Duration,
}

struct Job {
    generation: u64,
    scene: SceneId,
    options: SceneOptions,
}

/// Requests run ahead of time, only to fill the cache.
struct Anticipation {
    /// The newest request's generation when the anticipation was made: a newer request
    /// makes it stale.
    generation: u64,
    scene: SceneId,
    options: Vec<SceneOptions>,
}

/// How long the anticipating thread waits after a result before it starts: the viewer
/// ingests and draws the new recording meanwhile, and a user looks at it for longer.
const ANTICIPATION_DELAY: Duration = Duration::from_millis(300);

/// Niceness of the anticipating thread (Linux: per thread), so the viewer's drawing and the
/// user's own requests keep the cores first.
#[cfg(target_os = "linux")]
const ANTICIPATION_NICENESS: libc::c_int = 10;

/// A background thread that runs scenes, and one that anticipates requests.
pub struct Worker {
    jobs: Sender<Job>,
    done: Receiver<Finished>,
    latest: Arc<AtomicU64>,
    /// The newest request's progress (cancelled when a newer one comes).
    running: Option<Progress>,
    /// Time integrations kept across requests: ticking a method integrates that method only.
    cache: RunCache,
    anticipations: Sender<Anticipation>,
    /// The running anticipation's progress (cancelled by every request).
    anticipating: Arc<std::sync::Mutex<Option<Progress>>>,
    /// Anticipations finished (or failed) since the worker started; incremented after each
    /// request of an anticipation ran to its end.
    anticipated: Arc<AtomicU64>,
    /// Woken when a result is ready, so the UI takes it at once instead of at its next
    /// scheduled frame.
    waker: Arc<std::sync::Mutex<Option<egui::Context>>>,
}

impl Default for Worker {
    fn default() -> Self {
        Self::new()
    }
}

impl Worker {
    /// Starts the thread.
    pub fn new() -> Self {
        let (jobs, job_rx) = channel::<Job>();
        let (done_tx, done) = channel();
        let latest = Arc::new(AtomicU64::new(0));
        let latest_w = latest.clone();
        let waker: Arc<std::sync::Mutex<Option<egui::Context>>> = Arc::default();
        let waker_w = waker.clone();
        std::thread::Builder::new()
            .name("flexmodes-worker".into())
            .spawn(move || {
                while let Ok(mut job) = job_rx.recv() {
                    // Skip to the newest queued request.
                    while let Ok(newer) = job_rx.try_recv() {
                        job = newer;
                    }
                    let start = Instant::now();
                    let result = compute(&job);
                    // A request made meanwhile supersedes this one: drop it.
                    if job.generation < latest_w.load(Ordering::SeqCst) {
                        continue;
                    }
                    let finished = Finished {
                        generation: job.generation,
                        result,
                        elapsed: start.elapsed(),
                    };
                    if done_tx.send(finished).is_err() {
                        break;
                    }
                    if let Ok(guard) = waker_w.lock()
                        && let Some(ctx) = guard.as_ref()
                    {
                        ctx.request_repaint();
                    }
                }
            })
            .expect("spawning a thread");
        let cache = RunCache::new();
        let (anticipations, anticipation_rx) = channel::<Anticipation>();
        let anticipating: Arc<std::sync::Mutex<Option<Progress>>> = Arc::default();
        let anticipated = Arc::new(AtomicU64::new(0));
        let (cache_a, anticipating_a, anticipated_a, latest_a) = (
            cache.clone(),
            anticipating.clone(),
            anticipated.clone(),
            latest.clone(),
        );
        std::thread::Builder::new()
            .name("flexmodes-anticipate".into())
            .spawn(move || {
                lower_priority();
                while let Ok(mut next) = anticipation_rx.recv() {
                    // The viewer first draws the result just shown.
                    std::thread::sleep(ANTICIPATION_DELAY);
                    while let Ok(newer) = anticipation_rx.try_recv() {
                        next = newer;
                    }
                    let scene = scenes::get(next.scene);
                    for mut options in next.options {
                        let progress = Progress::new();
                        match anticipating_a.lock() {
                            Ok(mut slot) => *slot = Some(progress.clone()),
                            Err(_) => return,
                        }
                        // Checked after the progress is in its slot: a request either cancels
                        // it there or is seen here (it raises the generation first).
                        if next.generation < latest_a.load(Ordering::SeqCst) {
                            break;
                        }
                        options.progress = progress.clone();
                        options.cache = cache_a.clone();
                        // Only the cache's entries count; errors show when the user asks.
                        let _ = scene.execute(&options);
                        if progress.is_cancelled() {
                            break;
                        }
                        anticipated_a.fetch_add(1, Ordering::SeqCst);
                    }
                    if let Ok(mut slot) = anticipating_a.lock() {
                        *slot = None;
                    }
                }
            })
            .expect("spawning a thread");
        Self {
            jobs,
            done,
            latest,
            running: None,
            cache,
            anticipations,
            anticipating,
            anticipated,
            waker,
        }
    }

    /// Runs `options` of `scene` ahead of time at low priority, one after the other, to fill
    /// the cache (replacing anticipations not yet started). A [`Self::submit`] stops them.
    pub fn anticipate(&self, scene: SceneId, options: Vec<SceneOptions>) {
        let _ = self.anticipations.send(Anticipation {
            generation: self.latest.load(Ordering::SeqCst),
            scene,
            options,
        });
    }

    /// The progress of the anticipated request running now, if one runs.
    pub fn anticipation(&self) -> Option<Progress> {
        self.anticipating.lock().ok().and_then(|slot| slot.clone())
    }

    /// Anticipated requests that ran to their end since the worker started.
    pub fn anticipated(&self) -> u64 {
        self.anticipated.load(Ordering::SeqCst)
    }

    /// Entries in the cache shared by requests and anticipations.
    pub fn cached(&self) -> usize {
        self.cache.len()
    }

    /// Bytes those entries weigh (an estimate: see `CacheWeight`).
    pub fn cached_bytes(&self) -> usize {
        self.cache.bytes()
    }

    /// The most those entries may weigh, bytes.
    pub fn cache_budget(&self) -> usize {
        self.cache.budget()
    }

    /// Repaints `ctx` whenever a result is ready.
    pub fn wake(&self, ctx: &egui::Context) {
        if let Ok(mut guard) = self.waker.lock()
            && guard.is_none()
        {
            *guard = Some(ctx.clone());
        }
    }

    /// Requests a computation of generation `generation` (larger than any before) and cancels
    /// the previous one; returns the new request's progress handle.
    pub fn submit(
        &mut self,
        generation: u64,
        scene: SceneId,
        mut options: SceneOptions,
    ) -> Progress {
        // Newest generation first, so the cancelled job's error is dropped as superseded.
        self.latest.store(generation, Ordering::SeqCst);
        if let Some(old) = self.running.take() {
            old.cancel();
        }
        if let Ok(slot) = self.anticipating.lock()
            && let Some(anticipation) = slot.as_ref()
        {
            anticipation.cancel();
        }
        let progress = Progress::new();
        options.progress = progress.clone();
        options.cache = self.cache.clone();
        options.concurrent_integrations = crate::linalg::threads();
        self.running = Some(progress.clone());
        let _ = self.jobs.send(Job {
            generation,
            scene,
            options,
        });
        progress
    }

    /// How far the newest request's time integrations got.
    pub fn progress(&self) -> Option<ProgressReading> {
        self.running.as_ref().and_then(Progress::reading)
    }

    /// The phase the newest request is in (a refined reduction's factorisation, ...).
    pub fn phase(&self) -> Option<crate::PhaseReading> {
        self.running.as_ref().and_then(Progress::phase_reading)
    }

    /// A finished computation, if one is ready.
    pub fn poll(&self) -> Option<Finished> {
        self.done.try_recv().ok()
    }
}

/// Lowers the calling thread's scheduling priority (Linux gives each thread its own
/// niceness); elsewhere the thread runs at normal priority.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    // SAFETY: gettid and setpriority take no pointers; failure leaves the priority as it was.
    unsafe {
        let tid = libc::gettid();
        libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, ANTICIPATION_NICENESS);
    }
}

fn compute(job: &Job) -> Result<Computed, ExplorerError> {
    let (scene, options, generation) = (job.scene, &job.options, job.generation);
    let s = scenes::get(scene);
    let start = Instant::now();
    let out = s.execute(options).map_err(|e| ExplorerError::Scene {
        scene,
        error: Arc::new(e),
    })?;
    let compute_s = start.elapsed().as_secs_f64();
    // The window makes the layout active once the whole recording is in the viewer.
    let recorder = Recorder {
        recording_suffix: Some(generation.to_string()),
        default_blueprint_only: true,
        viewer_area: Some(super::VIEWER_AREA),
    };
    let start = Instant::now();
    let messages = recorder
        .messages(&out)
        .map_err(|e| ExplorerError::Recording {
            scene,
            error: Arc::new(e),
        })?;
    let messages_s = start.elapsed().as_secs_f64();
    Ok(Computed {
        scene,
        entity_paths: out.visuals.iter().map(|v| v.path().to_string()).collect(),
        blueprint: recorder.blueprint_key(&out),
        report: out.report,
        messages,
        compute_s,
        messages_s,
    })
}
