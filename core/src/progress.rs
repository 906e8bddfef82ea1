//! How far a running computation got, and the request that it stop.

use std::{
    sync::{
        Arc, Mutex,
        atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering},
    },
    time::Instant,
};

use crate::error::{Error, Result};

#[derive(Debug, Default)]
struct Shared {
    /// Shared with [`Progress::muted`] handles.
    cancelled: Arc<AtomicBool>,
    simulations: AtomicUsize,
    time_bits: AtomicU64,
    end_bits: AtomicU64,
    phase: Mutex<Option<(String, Instant)>>,
    phases: AtomicUsize,
    /// Every ended phase and its seconds, in order.
    ended: Mutex<Vec<(String, f64)>>,
}

/// The phase a computation is in (a reduction's factorisation, constraint modes,
/// eigensolve, ...).
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseReading {
    /// What runs.
    pub name: String,
    /// Phases started so far, this one included.
    pub number: usize,
    /// Seconds since it started.
    pub elapsed_s: f64,
}

/// A handle shared by a running computation and whoever waits for it: time integrations report
/// the simulated time, and the waiter may ask them to stop (a newer request superseded it).
///
/// The default handle is detached: it records nothing and never asks to stop. Clones share
/// their state; two handles compare equal when they share it (or are both detached).
#[derive(Debug, Clone, Default)]
pub struct Progress(Option<Arc<Shared>>);

/// A reading of a [`Progress`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgressReading {
    /// Time integrations started so far.
    pub simulations: usize,
    /// Simulated time reached by the current one, s.
    pub time: f64,
    /// Its end time, s.
    pub end_time: f64,
}

impl Progress {
    /// An attached handle (its clones see what it records).
    pub fn new() -> Self {
        Self(Some(Arc::default()))
    }

    /// A handle that stops when this one is cancelled (and cancels it) but whose readings
    /// nobody sees: for work running beside the one this handle reports (integrations of
    /// several methods at once). Detached stays detached.
    pub fn muted(&self) -> Self {
        Self(self.0.as_ref().map(|s| {
            Arc::new(Shared {
                cancelled: s.cancelled.clone(),
                ..Default::default()
            })
        }))
    }

    /// Asks the computation to stop at its next check.
    pub fn cancel(&self) {
        if let Some(s) = &self.0 {
            s.cancelled.store(true, Ordering::SeqCst);
        }
    }

    /// Whether [`cancel`](Self::cancel) was called.
    pub fn is_cancelled(&self) -> bool {
        self.0
            .as_ref()
            .is_some_and(|s| s.cancelled.load(Ordering::SeqCst))
    }

    /// `Err(Error::Cancelled)` once cancelled.
    pub fn check(&self) -> Result<()> {
        if self.is_cancelled() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }

    /// A time integration to `end_time` (s) starts.
    pub fn start_simulation(&self, end_time: f64) -> Result<()> {
        if let Some(s) = &self.0 {
            s.simulations.fetch_add(1, Ordering::SeqCst);
            s.time_bits.store(0f64.to_bits(), Ordering::SeqCst);
            s.end_bits.store(end_time.to_bits(), Ordering::SeqCst);
        }
        self.check()
    }

    /// The current time integration reached `time` (s); `Err(Error::Cancelled)` once cancelled.
    pub fn advance(&self, time: f64) -> Result<()> {
        if let Some(s) = &self.0 {
            s.time_bits.store(time.to_bits(), Ordering::SeqCst);
        }
        self.check()
    }

    /// A phase of a long computation starts: `Err(Error::Cancelled)` if the computation was
    /// cancelled meanwhile, so a superseded request stops at the next phase boundary.
    pub fn phase(&self, name: &str) -> Result<()> {
        self.check()?;
        if let Some(s) = &self.0 {
            s.phases.fetch_add(1, Ordering::SeqCst);
            if let Ok(mut p) = s.phase.lock() {
                if let Some((ended, started)) = p.take()
                    && let Ok(mut list) = s.ended.lock()
                {
                    list.push((ended, started.elapsed().as_secs_f64()));
                }
                *p = Some((name.to_string(), Instant::now()));
            }
        }
        Ok(())
    }

    /// The current phase; `None` when detached or before any phase.
    pub fn phase_reading(&self) -> Option<PhaseReading> {
        let s = self.0.as_ref()?;
        let p = s.phase.lock().ok()?;
        let (name, started) = p.as_ref()?;
        Some(PhaseReading {
            name: name.clone(),
            number: s.phases.load(Ordering::SeqCst),
            elapsed_s: started.elapsed().as_secs_f64(),
        })
    }

    /// Every phase so far with its seconds, the current one until now; empty when detached.
    /// A phase name that recurs (one per method) is listed each time.
    pub fn phase_times(&self) -> Vec<(String, f64)> {
        let Some(s) = &self.0 else {
            return Vec::new();
        };
        let mut out = s.ended.lock().map(|l| l.clone()).unwrap_or_default();
        if let Ok(p) = s.phase.lock()
            && let Some((name, started)) = p.as_ref()
        {
            out.push((name.clone(), started.elapsed().as_secs_f64()));
        }
        out
    }

    /// What was recorded so far; `None` when detached or before any time integration.
    pub fn reading(&self) -> Option<ProgressReading> {
        let s = self.0.as_ref()?;
        let simulations = s.simulations.load(Ordering::SeqCst);
        (simulations > 0).then(|| ProgressReading {
            simulations,
            time: f64::from_bits(s.time_bits.load(Ordering::SeqCst)),
            end_time: f64::from_bits(s.end_bits.load(Ordering::SeqCst)),
        })
    }
}

impl PartialEq for Progress {
    fn eq(&self, other: &Self) -> bool {
        same_shared(&self.0, &other.0)
    }
}

/// Whether two optional shared handles are the same one (or both absent): the equality of
/// handles that share state, where comparing contents would be meaningless.
pub fn same_shared<T: ?Sized>(a: &Option<Arc<T>>, b: &Option<Arc<T>>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => Arc::ptr_eq(a, b),
        _ => false,
    }
}
