//! Scene computation off the UI thread; a newer request supersedes older ones and stops a
//! running time integration at its next output step.

use std::{
    sync::{
        Arc,
        atomic::{AtomicU64, Ordering},
        mpsc::{Receiver, Sender, channel},
    },
    time::{Duration, Instant},
};

use rerun::external::egui;

use crate::{
    Progress, ProgressReading,
    record::Recorder,
    report::Report,
    scenes::{self, RunCache, SceneOptions},
};

/// A finished computation: the numbers, the panel text and the recording.
#[derive(Debug, Clone)]
pub struct Computed {
    /// Scene id.
    pub scene: String,
    /// The numeric report.
    pub report: Report,
    /// Entity paths logged.
    pub entity_paths: Vec<String>,
    /// The recording as `.rrd` bytes (for saving and for the viewer).
    pub rrd: Vec<u8>,
    /// Running the scene, s.
    pub compute_s: f64,
    /// Building and encoding the recording, s.
    pub encode_s: f64,
}

/// The outcome of one request.
#[derive(Debug)]
pub struct Finished {
    /// The request's generation.
    pub generation: u64,
    /// The result, or the error's cause chain.
    pub result: Result<Computed, String>,
    /// How long the computation took.
    pub elapsed: Duration,
}

struct Job {
    generation: u64,
    scene: String,
    options: SceneOptions,
    keep_user_layout: bool,
}

/// A background thread that runs scenes.
pub struct Worker {
    jobs: Sender<Job>,
    done: Receiver<Finished>,
    latest: Arc<AtomicU64>,
    /// The newest request's progress (cancelled when a newer one comes).
    running: Option<Progress>,
    /// Time integrations kept across requests: ticking a method integrates that method only.
    cache: RunCache,
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
                    let result = compute(&job, job.keep_user_layout);
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
        Self {
            jobs,
            done,
            latest,
            running: None,
            cache: RunCache::new(),
            waker,
        }
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
    /// `keep_user_layout`: send the scene's blueprint as the default only (the scene was
    /// shown before and the user may have arranged its views).
    pub fn submit(
        &mut self,
        generation: u64,
        scene: &str,
        mut options: SceneOptions,
        keep_user_layout: bool,
    ) -> Progress {
        // Newest generation first, so the cancelled job's error is dropped as superseded.
        self.latest.store(generation, Ordering::SeqCst);
        if let Some(old) = self.running.take() {
            old.cancel();
        }
        let progress = Progress::new();
        options.progress = progress.clone();
        options.cache = self.cache.clone();
        self.running = Some(progress.clone());
        let _ = self.jobs.send(Job {
            generation,
            scene: scene.into(),
            options,
            keep_user_layout,
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

fn compute(job: &Job, keep_user_layout: bool) -> Result<Computed, String> {
    let (scene, options, generation) = (&job.scene, &job.options, job.generation);
    let chain = |e: crate::Error| {
        let mut msg = e.to_string();
        let mut src = std::error::Error::source(&e);
        while let Some(s) = src {
            msg.push_str(&format!(": {s}"));
            src = s.source();
        }
        msg
    };
    let s = scenes::find(scene).map_err(chain)?;
    let start = Instant::now();
    let out = s.execute(options).map_err(chain)?;
    let compute_s = start.elapsed().as_secs_f64();
    let recorder = Recorder {
        recording_suffix: Some(generation.to_string()),
        keep_user_layout,
    };
    let start = Instant::now();
    let rrd = recorder.encode(&out).map_err(chain)?;
    let encode_s = start.elapsed().as_secs_f64();
    Ok(Computed {
        scene: scene.clone(),
        entity_paths: out.visuals.iter().map(|v| v.path().to_string()).collect(),
        report: out.report,
        rrd,
        compute_s,
        encode_s,
    })
}
