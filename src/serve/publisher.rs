//! One recording computed and published at a time: the teacher's requests (terminal or
//! control page) go to a single worker; a request made while one computes replaces the one
//! waiting, so requests never stack up behind a slow scene.

use std::{
    sync::{Arc, Condvar, Mutex, PoisonError},
    thread::JoinHandle,
};

use rerun::external::re_log_types::LogMsg;

use crate::Result;

/// A recording to compute and publish: its label (the command that asked for it) and the
/// computation.
pub struct PublishJob {
    /// What the teacher asked for, as a command line (`slab-modes --method cb`).
    pub label: String,
    /// Computes the recording's messages.
    pub compute: Box<dyn FnOnce() -> Result<Vec<LogMsg>> + Send>,
}

/// What the publisher did last, for the control page.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum PublishStatus {
    /// Nothing was asked for yet.
    #[default]
    Idle,
    /// This request is being computed.
    Computing(String),
    /// This request was published to every viewer, in this many messages.
    Published { label: String, messages: usize },
    /// This request failed: the label and the error.
    Failed(String, String),
}

#[derive(Default)]
struct Slot {
    next: Option<PublishJob>,
    stop: bool,
    status: PublishStatus,
}

/// The worker that computes and publishes requests one at a time.
pub struct Publisher {
    shared: Arc<(Mutex<Slot>, Condvar)>,
    worker: Option<JoinHandle<()>>,
}

fn lock(m: &Mutex<Slot>) -> std::sync::MutexGuard<'_, Slot> {
    m.lock().unwrap_or_else(PoisonError::into_inner)
}

impl Publisher {
    /// Starts the worker; `publish` sends a computed recording to the viewers, `announce`
    /// hears of each request's end (published or failed), for the teacher's terminal.
    pub fn start(
        publish: impl Fn(Vec<LogMsg>) + Send + 'static,
        announce: impl Fn(&PublishStatus) + Send + 'static,
    ) -> Self {
        let shared = Arc::new((Mutex::new(Slot::default()), Condvar::new()));
        let inner = shared.clone();
        let worker = std::thread::spawn(move || {
            let (slot, wake) = &*inner;
            loop {
                let job = {
                    let mut s = lock(slot);
                    while s.next.is_none() && !s.stop {
                        s = wake.wait(s).unwrap_or_else(PoisonError::into_inner);
                    }
                    if s.stop {
                        return;
                    }
                    let job = s.next.take().expect("woken with a job");
                    s.status = PublishStatus::Computing(job.label.clone());
                    job
                };
                let status = match (job.compute)() {
                    Ok(messages) => {
                        let count = messages.len();
                        publish(messages);
                        PublishStatus::Published {
                            label: job.label,
                            messages: count,
                        }
                    }
                    Err(e) => PublishStatus::Failed(job.label, e.to_string()),
                };
                announce(&status);
                lock(slot).status = status;
            }
        });
        Self {
            shared,
            worker: Some(worker),
        }
    }

    /// Queues `job`, replacing the one waiting (not the one computing); returns the label of
    /// the job it replaced.
    pub fn submit(&self, job: PublishJob) -> Option<String> {
        let (slot, wake) = &*self.shared;
        let replaced = lock(slot).next.replace(job).map(|j| j.label);
        wake.notify_one();
        replaced
    }

    /// What the worker did last (or is doing).
    pub fn status(&self) -> PublishStatus {
        lock(&self.shared.0).status.clone()
    }

    /// Whether a request waits behind the one computing.
    pub fn queued(&self) -> Option<String> {
        lock(&self.shared.0).next.as_ref().map(|j| j.label.clone())
    }
}

impl Drop for Publisher {
    /// Drops the waiting request and lets the one computing finish.
    fn drop(&mut self) {
        {
            let mut s = lock(&self.shared.0);
            s.stop = true;
            s.next = None;
        }
        self.shared.1.notify_all();
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}
