//! What a recording's default blueprint holds, compared: a switch to a recording whose views
//! are the ones shown, each showing what fits where the shown one looks, keeps the user's
//! arrangement of the views in the desktop explorer.

use super::{Bounds, Layout, RecordingContent, eye::series_range};

/// A recording's layout (titles fitted to the viewer's area) and what each view starts
/// showing: the bounds a 3D view's camera or a 2D view frames, the value range a time series
/// shows, and the timeline the time panel plays. Two recordings with equal keys get the same
/// blueprint (its ids follow from the layout, and nothing else enters it).
#[derive(Debug, Clone, PartialEq)]
pub struct BlueprintKey {
    /// The views and their arrangement.
    pub layout: Layout,
    /// Per view origin: the bounds of what it shows (m) and its series' value range.
    framing: Vec<(String, Option<Bounds>, Option<[f64; 2]>)>,
    /// The timeline the time panel plays.
    timeline: Option<String>,
}

/// The least share of the shown extent (per axis, and of a value range) the new contents must
/// span for the shown framing to be kept: less, and the view would show them small in a corner.
pub const KEPT_FILL: f64 = 0.5;

impl BlueprintKey {
    /// Whether a view arranged for `self` shows `next` as well: the same views and timeline,
    /// and in each view `next`'s bounds (3D and 2D views) and value range (time series)
    /// inside `self`'s, spanning at least `KEPT_FILL` (half) of them along every axis where
    /// `self` has an extent. Nothing drawn in both is the same framing too.
    pub fn frames(&self, next: &BlueprintKey) -> bool {
        self.layout == next.layout
            && self.timeline == next.timeline
            && self.framing.len() == next.framing.len()
            && self.framing.iter().zip(&next.framing).all(|(shown, new)| {
                shown.0 == new.0
                    && match (&shown.1, &new.1) {
                        (None, None) => true,
                        (Some(a), Some(b)) => {
                            (0..3).all(|i| within([a.lo[i], a.hi[i]], [b.lo[i], b.hi[i]]))
                        }
                        _ => false,
                    }
                    && match (&shown.2, &new.2) {
                        (None, None) => true,
                        (Some(a), Some(b)) => within(*a, *b),
                        _ => false,
                    }
            })
    }

    /// The key of `out` laid out as `layout` (its fitted layout).
    pub fn of(layout: Layout, out: &RecordingContent) -> Self {
        let framing = layout
            .origins()
            .into_iter()
            .map(|origin| {
                let bounds = Bounds::of(&origin, &out.visuals);
                let range = series_range(&origin, &out.visuals);
                (origin, bounds, range)
            })
            .collect();
        Self {
            layout,
            framing,
            timeline: out.timeline.clone(),
        }
    }
}

/// Whether the interval `inner` lies within `outer` (to round-off) and spans at least
/// [`KEPT_FILL`] of it; a point-like `outer` (no extent on this axis) must hold `inner` alone.
fn within(outer: [f64; 2], inner: [f64; 2]) -> bool {
    let span = outer[1] - outer[0];
    let slack = 1e-9 * (outer[0].abs().max(outer[1].abs()) + span).max(f64::MIN_POSITIVE);
    let inside = inner[0] >= outer[0] - slack && inner[1] <= outer[1] + slack;
    inside && (span <= slack || inner[1] - inner[0] >= KEPT_FILL * span)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(bounds: Option<([f64; 3], [f64; 3])>, range: Option<[f64; 2]>) -> BlueprintKey {
        BlueprintKey {
            layout: Layout::view3d("body", "/body"),
            framing: vec![(
                "/body".into(),
                bounds.map(|(lo, hi)| Bounds { lo, hi }),
                range,
            )],
            timeline: Some("time".into()),
        }
    }

    #[test]
    fn a_framing_is_kept_for_contents_inside_it_that_fill_it_enough() {
        let shown = key(Some(([0.0; 3], [4.0, 2.0, 0.0])), Some([-1.0, 1.0]));
        assert!(shown.frames(&shown), "the same contents");
        // A method unticked: its lines gone, the rest inside and filling most of it.
        assert!(shown.frames(&key(
            Some(([0.5, 0.0, 0.0], [4.0, 1.5, 0.0])),
            Some([-0.8, 1.0])
        )));
        // A mode more in a new row, or a method ticked whose line leaves the range: refused.
        assert!(!shown.frames(&key(Some(([0.0; 3], [4.0, 3.0, 0.0])), Some([-1.0, 1.0]))));
        assert!(!shown.frames(&key(Some(([0.0; 3], [4.0, 2.0, 0.0])), Some([-1.0, 1.2]))));
        // Contents a tenth of the view: shown small in a corner, so refused.
        assert!(!shown.frames(&key(Some(([0.0; 3], [0.4, 0.2, 0.0])), Some([-1.0, 1.0]))));
        assert!(!shown.frames(&key(Some(([0.0; 3], [4.0, 2.0, 0.0])), Some([0.0, 0.1]))));
        // A flat axis (z of a plane) holds a flat axis only; nothing drawn against something.
        assert!(!shown.frames(&key(Some(([0.0; 3], [4.0, 2.0, 1.0])), Some([-1.0, 1.0]))));
        assert!(!shown.frames(&key(None, Some([-1.0, 1.0]))));
        // Another layout or timeline is never kept.
        let mut other = shown.clone();
        other.layout = Layout::view3d("body", "/other");
        assert!(!shown.frames(&other));
        other = shown.clone();
        other.timeline = None;
        assert!(!shown.frames(&other));
    }
}
