//! Results of expensive steps kept between requests of the desktop explorer.

use std::{
    any::Any,
    collections::HashMap,
    sync::{Arc, Mutex},
};

use crate::{
    Result,
    dynamics::{Simulation, System},
};

/// Entries kept at most (a slab simulation's samples are about 1 MB on App. B).
const CAPACITY: usize = 64;
/// Bytes kept at most, by the entries' [`CacheWeight`]: an integration without reduction on
/// the explorer's largest simulation mesh (2 295 DOF) holds about 200 MB, so 64 of them
/// would not fit a desktop's memory; 512 MiB keeps two of them, or all the integrations of
/// the App. B slab's switches. The explorer's memory over 50 switches is measured against it
/// (`gui --screenshot --toggle ... --repeat 50` prints both).
const BYTE_BUDGET: usize = 512 << 20;

/// What a cached value weighs, bytes on the heap (an estimate; see the implementations).
pub trait CacheWeight {
    /// Bytes held.
    fn bytes(&self) -> usize;
}

impl CacheWeight for (System, Simulation) {
    fn bytes(&self) -> usize {
        self.0.heap_bytes() + self.1.heap_bytes()
    }
}

struct Entry {
    value: Arc<dyn Any + Send + Sync>,
    bytes: usize,
    /// When it was last stored or served (a counter): the least recent goes first.
    used: u64,
}

struct Entries {
    map: HashMap<String, Entry>,
    clock: u64,
    bytes: usize,
    /// Limits: entries and bytes.
    capacity: usize,
    budget: usize,
}

/// Results of time integrations (and other expensive steps) keyed by everything that determines
/// them, so a request that only ticks another method integrates that method alone. At most
/// 64 entries and 512 MiB ([`CacheWeight`]) are kept; beyond either, the least recently used
/// entries go.
///
/// The default cache is detached: it keeps nothing and every step runs (the CLI). Clones share
/// their entries; two caches compare equal when they share them (or are both detached).
#[derive(Clone, Default)]
pub struct RunCache(Option<Arc<Mutex<Entries>>>);

impl RunCache {
    /// An attached cache with the default limits.
    pub fn new() -> Self {
        Self::with_limits(CAPACITY, BYTE_BUDGET)
    }

    /// An attached cache keeping at most `capacity` entries and `budget` bytes.
    pub fn with_limits(capacity: usize, budget: usize) -> Self {
        Self(Some(Arc::new(Mutex::new(Entries {
            map: HashMap::new(),
            clock: 0,
            bytes: 0,
            capacity,
            budget,
        }))))
    }

    /// The value stored under `key`, or `run()`'s, stored when it succeeds and fits the
    /// budget by itself. The lock is not held while `run` works.
    pub fn get_or_run<T: Any + Send + Sync + CacheWeight, E>(
        &self,
        key: String,
        run: impl FnOnce() -> Result<T, E>,
    ) -> Result<Arc<T>, E> {
        let Some(entries) = &self.0 else {
            return run().map(Arc::new);
        };
        let cached = entries.lock().ok().and_then(|mut e| {
            e.clock += 1;
            let now = e.clock;
            let entry = e.map.get_mut(&key)?;
            entry.used = now;
            entry.value.clone().downcast::<T>().ok()
        });
        if let Some(v) = cached {
            return Ok(v);
        }
        let value = Arc::new(run()?);
        if let Ok(mut e) = entries.lock() {
            e.store(key, value.clone(), value.bytes());
        }
        Ok(value)
    }

    /// Entries kept.
    pub fn len(&self) -> usize {
        self.0
            .as_ref()
            .and_then(|e| e.lock().ok().map(|e| e.map.len()))
            .unwrap_or(0)
    }

    /// Whether the cache keeps nothing by design (the command line's default).
    pub fn is_detached(&self) -> bool {
        self.0.is_none()
    }

    /// Whether nothing is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The most the kept entries may weigh, bytes (0 for a detached cache).
    pub fn budget(&self) -> usize {
        self.0
            .as_ref()
            .and_then(|e| e.lock().ok().map(|e| e.budget))
            .unwrap_or(0)
    }

    /// Bytes the kept entries weigh ([`CacheWeight`]).
    pub fn bytes(&self) -> usize {
        self.0
            .as_ref()
            .and_then(|e| e.lock().ok().map(|e| e.bytes))
            .unwrap_or(0)
    }
}

impl Entries {
    /// Stores `value` under `key` and evicts the least recently used other entries until the
    /// limits hold; a value heavier than the whole budget is not stored.
    fn store(&mut self, key: String, value: Arc<dyn Any + Send + Sync>, bytes: usize) {
        if bytes > self.budget || self.capacity == 0 {
            return;
        }
        self.clock += 1;
        let used = self.clock;
        if let Some(old) = self.map.insert(key.clone(), Entry { value, bytes, used }) {
            self.bytes -= old.bytes;
        }
        self.bytes += bytes;
        while self.bytes > self.budget || self.map.len() > self.capacity {
            let Some(oldest) = self
                .map
                .iter()
                .filter(|(k, _)| **k != key)
                .min_by_key(|(_, e)| e.used)
                .map(|(k, _)| k.clone())
            else {
                break;
            };
            if let Some(gone) = self.map.remove(&oldest) {
                self.bytes -= gone.bytes;
            }
        }
    }
}

impl std::fmt::Debug for RunCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.0 {
            None => f.write_str("RunCache(detached)"),
            Some(_) => write!(
                f,
                "RunCache({} entries, {} bytes)",
                self.len(),
                self.bytes()
            ),
        }
    }
}

impl PartialEq for RunCache {
    fn eq(&self, other: &Self) -> bool {
        flexmodes_core::same_shared(&self.0, &other.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// A value that weighs what it says.
    struct Blob(usize);

    impl CacheWeight for Blob {
        fn bytes(&self) -> usize {
            self.0
        }
    }

    /// Fetches `key` (weighing `bytes` when it runs) and says whether it ran.
    fn fetch(cache: &RunCache, key: &str, bytes: usize) -> bool {
        let ran = Cell::new(false);
        let v = cache
            .get_or_run(key.into(), || {
                ran.set(true);
                Ok::<_, crate::Error>(Blob(bytes))
            })
            .unwrap();
        assert_eq!(v.0, bytes, "{key}");
        ran.get()
    }

    #[test]
    fn the_least_recently_used_entries_go_when_the_bytes_run_out() {
        let cache = RunCache::with_limits(10, 100);
        assert!(fetch(&cache, "a", 40));
        assert!(fetch(&cache, "b", 40));
        // a served again: b is now the least recent.
        assert!(!fetch(&cache, "a", 40));
        assert!(fetch(&cache, "c", 40));
        assert_eq!((cache.len(), cache.bytes()), (2, 80));
        assert!(!fetch(&cache, "a", 40), "kept");
        assert!(!fetch(&cache, "c", 40), "kept");
        assert!(fetch(&cache, "b", 40), "evicted, runs again");
        // One entry heavier than the whole budget is served but not kept, and evicts nothing.
        assert!(fetch(&cache, "huge", 101));
        assert!(fetch(&cache, "huge", 101));
        assert_eq!(cache.bytes(), 80);
        assert!(cache.bytes() <= 100);
    }

    #[test]
    fn the_entry_count_is_bounded_too() {
        let cache = RunCache::with_limits(3, usize::MAX);
        for (k, key) in ["a", "b", "c", "d", "e"].iter().enumerate() {
            assert!(fetch(&cache, key, k + 1));
            assert!(cache.len() <= 3);
        }
        assert_eq!(cache.len(), 3);
        // c, d, e kept (3 + 4 + 5 bytes); a and b gone.
        assert_eq!(cache.bytes(), 12);
        assert!(!fetch(&cache, "c", 3));
        assert!(fetch(&cache, "a", 1));
    }

    #[test]
    fn failures_are_not_kept_and_a_detached_cache_keeps_nothing() {
        let cache = RunCache::new();
        let failed = cache.get_or_run::<Blob, _>("x".into(), || {
            Err(crate::Error::InvalidOption {
                option: "--method",
                scene: None,
                reason: "no".into(),
            })
        });
        assert!(failed.is_err());
        assert!(cache.is_empty());
        let detached = RunCache::default();
        assert!(fetch(&detached, "a", 1));
        assert!(fetch(&detached, "a", 1));
        assert_eq!((detached.len(), detached.bytes()), (0, 0));
    }
}
