//! The palette: one colour per method, the same in the 3-D views, the bar charts and the
//! charts of every scene and bench, and the references' greys.

use super::Color;
use crate::reduction::Method;

/// A fixed colour per method so views compare at a glance: the same in the 3-D views, the bar
/// charts and the charts of every scene. Each reads on the viewer's dark and light themes
/// alike: its relative luminance lies between 0.08 and 0.37, a contrast of at least 2.5:1
/// against black and against white (tested).
pub fn method_color(m: Method) -> Color {
    match m {
        Method::NoReduction => [120, 120, 150, 255],
        Method::Guyan => [230, 120, 0, 255],
        Method::ModalTruncation => [210, 50, 50, 255],
        Method::CraigBampton => [40, 110, 230, 255],
        Method::ModeCondensation => [30, 150, 60, 255],
        Method::Eitelberg => [160, 70, 200, 255],
        Method::MacNealRubin => [220, 60, 140, 255],
        Method::BenfieldHruda => [0, 150, 160, 255],
        Method::MomentMatching => [150, 150, 0, 255],
        Method::BalancedTruncation => [150, 90, 40, 255],
    }
}

/// Colour of the undeformed bodies and references (mid grey: it reads on both themes).
pub const REFERENCE: Color = [150, 150, 150, 255];

/// Colour of a chart's Pareto front: dark grey, where white vanished on the light theme.
pub const PARETO: Color = [110, 110, 110, 255];

/// Colour of multi-level substructuring (AMLS), which is no [`Method`] of a single body's
/// reduction: violet, apart from every method's colour.
pub const AMLS: Color = [120, 60, 210, 255];

/// Colour of a reduced model with inertia-load residual vectors beside the same model
/// without them (drawn in its method's colour): burnt orange, relative luminance 0.2.
pub const RESIDUAL_VECTORS: Color = [200, 90, 20, 255];

/// Colour of the separators of a substructure tree's `level` (0: the root), cycling through
/// six of the palette's colours; the leaves are drawn in [`REFERENCE`] grey.
pub fn level_color(level: usize) -> Color {
    const LEVELS: [Color; 6] = [
        [230, 120, 0, 255],
        [40, 110, 230, 255],
        [30, 150, 60, 255],
        AMLS,
        [220, 60, 140, 255],
        [0, 150, 160, 255],
    ];
    LEVELS[level % LEVELS.len()]
}

/// Colour of the undeformed ghost beside a body drawn with magnified deflections.
pub const REFERENCE_GHOST: Color = [150, 150, 150, 110];

#[cfg(test)]
mod palette_tests {
    use super::*;

    /// Relative luminance (WCAG) of an sRGB colour.
    fn luminance(c: Color) -> f64 {
        let lin = |v: u8| {
            let v = f64::from(v) / 255.0;
            if v <= 0.04045 {
                v / 12.92
            } else {
                ((v + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * lin(c[0]) + 0.7152 * lin(c[1]) + 0.0722 * lin(c[2])
    }

    const ALL: [Method; 10] = Method::ALL;

    /// Contrast at least 2.5:1 against both black and white, and the methods told apart.
    #[test]
    fn every_colour_reads_on_both_themes_and_the_methods_differ() {
        let contrast = |a: f64, b: f64| (a.max(b) + 0.05) / (a.min(b) + 0.05);
        for c in ALL
            .map(method_color)
            .into_iter()
            .chain([REFERENCE, PARETO])
            .chain((0..6).map(level_color))
        {
            let l = luminance(c);
            assert!(
                contrast(l, 0.0) >= 2.5 && contrast(l, 1.0) >= 2.5,
                "{c:?}: {l}"
            );
        }
        for (i, a) in ALL.iter().enumerate() {
            for b in &ALL[i + 1..] {
                let (x, y) = (method_color(*a), method_color(*b));
                let d: i32 = (0..3)
                    .map(|k| (i32::from(x[k]) - i32::from(y[k])).abs())
                    .sum();
                assert!(d >= 90, "{a:?} and {b:?} too alike: {x:?} {y:?}");
            }
        }
    }

    /// The browser check and the explorer's switch check count these colours: their tables
    /// must be this one.
    #[test]
    fn the_screenshot_checks_count_these_colours() {
        let scripts = [
            (
                "check_serve.py",
                include_str!("../../assets/serve/check_serve.py"),
            ),
            (
                "switch_frames.py",
                include_str!("../../assets/gui/switch_frames.py"),
            ),
        ];
        for (name, script) in scripts {
            for m in ALL {
                let c = method_color(m);
                let line = format!("\"{}\": ({}, {}, {}),", m.id(), c[0], c[1], c[2]);
                assert!(script.contains(&line), "{name} lacks {line}");
            }
        }
    }
}
