//! Results of expensive steps kept between requests of the desktop explorer.

use std::{
    any::Any,
    collections::HashMap,
    sync::{Arc, Mutex},
};

use crate::Result;

/// Entries kept before the cache starts over (a slab simulation's samples are about 1 MB).
const CAPACITY: usize = 64;

type Entries = HashMap<String, Arc<dyn Any + Send + Sync>>;

/// Results of time integrations (and other expensive steps) keyed by everything that determines
/// them, so a request that only ticks another method integrates that method alone.
///
/// The default cache is detached: it keeps nothing and every step runs (the CLI). Clones share
/// their entries; two caches compare equal when they share them (or are both detached).
#[derive(Clone, Default)]
pub struct RunCache(Option<Arc<Mutex<Entries>>>);

impl RunCache {
    /// An attached cache.
    pub fn new() -> Self {
        Self(Some(Arc::default()))
    }

    /// The value stored under `key`, or `run()`'s, stored when it succeeds. The lock is not
    /// held while `run` works.
    pub fn get_or_run<T: Any + Send + Sync>(
        &self,
        key: String,
        run: impl FnOnce() -> Result<T>,
    ) -> Result<Arc<T>> {
        let Some(entries) = &self.0 else {
            return run().map(Arc::new);
        };
        let cached = entries
            .lock()
            .ok()
            .and_then(|e| e.get(&key).cloned())
            .and_then(|v| v.downcast::<T>().ok());
        if let Some(v) = cached {
            return Ok(v);
        }
        let value = Arc::new(run()?);
        if let Ok(mut e) = entries.lock() {
            if e.len() >= CAPACITY {
                e.clear();
            }
            e.insert(key, value.clone());
        }
        Ok(value)
    }

    /// Entries kept.
    pub fn len(&self) -> usize {
        self.0
            .as_ref()
            .and_then(|e| e.lock().ok().map(|e| e.len()))
            .unwrap_or(0)
    }

    /// Whether nothing is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl std::fmt::Debug for RunCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.0 {
            None => f.write_str("RunCache(detached)"),
            Some(_) => write!(f, "RunCache({} entries)", self.len()),
        }
    }
}

impl PartialEq for RunCache {
    fn eq(&self, other: &Self) -> bool {
        crate::progress::same_shared(&self.0, &other.0)
    }
}
