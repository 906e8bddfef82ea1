//! The mark of an out-of-date view: while the explorer computes a new result or the viewer
//! takes it in, the previous one stays on screen with this badge over it.

use rerun::external::egui;

use super::{Explorer, viewer_handoff::HandoffState};

impl Explorer {
    /// Whether the view shows an older result than the controls ask for, and why (computing
    /// or loading into the viewer); `None` when it is up to date.
    pub fn updating(&self) -> Option<String> {
        if let Some(since) = self.computing_since {
            let mut text = format!("updating: computing {:.1} s", since.elapsed().as_secs_f64());
            if let Some(r) = self.worker.progress() {
                text.push_str(&format!(" · t = {:.2} of {:.2} s", r.time, r.end_time));
            }
            return Some(text);
        }
        match self.viewer_state {
            HandoffState::Loading { queued } => Some(format!(
                "updating: loading the new result into the viewer ({queued} messages left)"
            )),
            HandoffState::Capturing | HandoffState::Covering { .. } => {
                Some("updating: laying out the new result".into())
            }
            HandoffState::Idle => None,
        }
    }

    /// Marks the view as out of date while it shows the previous result: a badge at the
    /// top right of the window.
    pub fn updating_badge(&self, ctx: &egui::Context) {
        let Some(text) = self.updating() else { return };
        // Above the cover of a switch (see `ViewerHandoff`).
        egui::Area::new(egui::Id::new("flexmodes-updating"))
            .order(egui::Order::Tooltip)
            .anchor(egui::Align2::RIGHT_TOP, egui::vec2(-16.0, 40.0))
            .interactable(false)
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.horizontal(|ui| {
                        ui.spinner();
                        ui.label(text);
                    });
                    ui.label(
                        egui::RichText::new("the view shows the previous result until then")
                            .small(),
                    );
                });
            });
    }
}
