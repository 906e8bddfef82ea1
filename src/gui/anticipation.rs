//! What the explorer runs ahead of time: the requests one click away, handed to the worker's
//! low-priority thread so their integrations are cached when the user asks.

use super::{Controls, Explorer};
use crate::scenes;

impl Explorer {
    /// The controls one click away that need new time integrations: one kept mode more or
    /// fewer, and each of the scene's methods not ticked, ticked. Only simulations: their
    /// integrations are what a switch waits for, and what the cache keeps.
    pub fn likely_next(&self) -> Vec<Controls> {
        let c = scenes::get(self.controls.scene).info.controls;
        if c.end_time.is_none() {
            return Vec::new();
        }
        let mut out = Vec::new();
        if c.modes.is_some() {
            out.push(Controls {
                modes: self.controls.modes + 1,
                ..self.controls.clone()
            });
            if self.controls.modes > 0 {
                out.push(Controls {
                    modes: self.controls.modes - 1,
                    ..self.controls.clone()
                });
            }
        }
        for &m in c.methods {
            if !self.controls.methods.contains(&m) {
                let mut next = self.controls.clone();
                next.methods.push(m);
                out.push(next);
            }
        }
        out
    }

    /// Hands [`Self::likely_next`] to the worker to run ahead of time.
    pub(super) fn anticipate(&mut self) {
        let body = self.loaded_body().ok().flatten();
        let options = self
            .likely_next()
            .iter()
            .filter_map(|c| c.options_with(body.as_ref()).ok())
            .collect::<Vec<_>>();
        if !options.is_empty() {
            self.worker.anticipate(self.controls.scene, options);
        }
    }
}
