//! Where a 3D view's camera starts: looking across everything the view shows, so that a row
//! of bodies side by side reads as a row and none is cut off.

use super::Visual;

/// A camera of a 3D view (z up), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Eye {
    /// Where the camera is.
    pub position: [f64; 3],
    /// The point it looks at (and orbits about).
    pub look_target: [f64; 3],
    /// Its up direction.
    pub up: [f64; 3],
}

/// The viewer's vertical field of view, rad (55°).
const FOV_Y: f64 = 55.0 * std::f64::consts::PI / 180.0;
/// Room left around the contents, as a factor on the fitting distance.
const MARGIN: f64 = 1.15;
/// The camera's elevation above the horizontal, rad (30°).
const ELEVATION: f64 = 30.0 * std::f64::consts::PI / 180.0;
/// How far the camera turns from square-on to the row, towards its start, rad (20°): enough
/// to see the bodies' depth, little enough that the far end stays large.
const SKEW: f64 = 20.0 * std::f64::consts::PI / 180.0;

/// Axis-aligned bounds of points, m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Smallest coordinates.
    pub lo: [f64; 3],
    /// Largest coordinates.
    pub hi: [f64; 3],
}

impl Bounds {
    fn add(bounds: &mut Option<Bounds>, p: [f64; 3]) {
        if !p.iter().all(|x| x.is_finite()) {
            return;
        }
        let b = bounds.get_or_insert(Bounds { lo: p, hi: p });
        b.lo = [0, 1, 2].map(|i| b.lo[i].min(p[i]));
        b.hi = [0, 1, 2].map(|i| b.hi[i].max(p[i]));
    }

    /// The bounds of every point drawn under entity `origin` (a view's origin, with or without
    /// its leading slash) by `visuals`, each moved by the [`Visual::Offset`]s of its entity
    /// and its ancestors. `None` when nothing is drawn there.
    pub fn of(origin: &str, visuals: &[Visual]) -> Option<Bounds> {
        let origin = origin.trim_start_matches('/');
        let under = |path: &str, root: &str| {
            root.is_empty() || path == root || path.starts_with(&format!("{root}/"))
        };
        let shift = |path: &str| {
            let mut t = [0.0; 3];
            for v in visuals {
                if let Visual::Offset {
                    path: p,
                    translation,
                } = v
                    && under(path, p)
                {
                    for i in 0..3 {
                        t[i] += translation[i];
                    }
                }
            }
            t
        };
        let mut bounds = None;
        for v in visuals.iter().filter(|v| under(v.path(), origin)) {
            let t = shift(v.path());
            let mut add = |p: [f64; 3]| Self::add(&mut bounds, [0, 1, 2].map(|i| p[i] + t[i]));
            match v {
                Visual::Wireframe { geometry, .. } => geometry.nodes.iter().for_each(|&p| add(p)),
                Visual::Mode {
                    geometry, shape, ..
                } => {
                    for (p, s) in geometry.nodes.iter().zip(shape) {
                        add([0, 1, 2].map(|i| p[i] + s[i]));
                        add([0, 1, 2].map(|i| p[i] - s[i]));
                    }
                }
                Visual::Trajectory { positions, .. } => {
                    positions.iter().flatten().for_each(|&p| add(p));
                }
                Visual::RigidTrajectory {
                    geometry,
                    translations,
                    rotations,
                    ..
                } => {
                    for (r0, columns) in translations.iter().zip(rotations) {
                        for x in &geometry.nodes {
                            add([0, 1, 2].map(|i| {
                                r0[i] + (0..3).map(|c| columns[c][i] * x[c]).sum::<f64>()
                            }));
                        }
                    }
                }
                Visual::FrameAxes { origins, .. } => origins.iter().for_each(|&p| add(p)),
                Visual::Label3D { position, .. } => add(*position),
                // A chart's text anchors, its picture's corners among them, drawn y down:
                // stored y up as the views' bounds are (the blueprint flips them back).
                Visual::Text2D { points, .. } => {
                    points.iter().for_each(|p| add([p[0], -p[1], 0.0]));
                }
                _ => {}
            }
        }
        bounds
    }
}

/// The range of the values of every [`Visual::Series`] under entity `origin` (with or
/// without its leading slash); `None` when none is there or none is finite.
pub fn series_range(origin: &str, visuals: &[Visual]) -> Option<[f64; 2]> {
    let origin = origin.trim_start_matches('/');
    let mut range: Option<[f64; 2]> = None;
    for v in visuals {
        if let Visual::Series { path, values, .. } = v
            && (origin.is_empty() || path == origin || path.starts_with(&format!("{origin}/")))
        {
            for &x in values.iter().filter(|x| x.is_finite()) {
                let r = range.get_or_insert([x, x]);
                r[0] = r[0].min(x);
                r[1] = r[1].max(x);
            }
        }
    }
    range
}

impl Eye {
    /// The camera (z up) that frames `bounds` in a view `aspect` times wider than high: it
    /// looks at their centre across the longer horizontal extent, turned `SKEW` from
    /// square-on and raised `ELEVATION`, from the nearest place where every corner of the
    /// bounds lies inside the viewer's field of view (55° high, `aspect` × as wide) shrunk by
    /// `MARGIN`, perspective included.
    pub fn framing(bounds: &Bounds, aspect: f64) -> Eye {
        let centre = [0, 1, 2].map(|i| 0.5 * (bounds.lo[i] + bounds.hi[i]));
        let extent = [0, 1, 2].map(|i| bounds.hi[i] - bounds.lo[i]);
        // Unit vectors along the row (the longer horizontal extent) and across it.
        let (along, across) = if extent[0] >= extent[1] {
            ([1.0, 0.0], [0.0, -1.0])
        } else {
            ([0.0, 1.0], [1.0, 0.0])
        };
        let (long, short) = (extent[0].max(extent[1]), extent[0].min(extent[1]));
        let tan_y = (0.5 * FOV_Y).tan();
        let tan_x = aspect.clamp(0.2, 5.0) * tan_y;
        let horizontal = [0, 1].map(|i| across[i] * SKEW.cos() - along[i] * SKEW.sin());
        // From the target towards the eye, and the camera's right and up.
        let direction = [
            horizontal[0] * ELEVATION.cos(),
            horizontal[1] * ELEVATION.cos(),
            ELEVATION.sin(),
        ];
        let forward = direction.map(|x| -x);
        let right = normalised(cross(forward, [0.0, 0.0, 1.0]));
        let up = cross(right, forward);
        // The nearest eye on that line that sees every corner of the bounds inside the field
        // of view shrunk by the margin: a corner q (from the centre) at depth q·f + d must have
        // |q·r| ≤ tan_x (q·f + d) / margin and |q·u| ≤ tan_y (q·f + d) / margin.
        let mut distance = 1e-3 * long.max(short).max(extent[2]).max(1e-9);
        for corner in 0..8 {
            let q = [0, 1, 2].map(|i| {
                if corner >> i & 1 == 1 {
                    bounds.hi[i] - centre[i]
                } else {
                    bounds.lo[i] - centre[i]
                }
            });
            let depth = dot(q, forward);
            distance = distance
                .max(MARGIN * dot(q, right).abs() / tan_x - depth)
                .max(MARGIN * dot(q, up).abs() / tan_y - depth);
        }
        Eye {
            position: [0, 1, 2].map(|i| centre[i] + distance * direction[i]),
            look_target: centre,
            up: [0.0, 0.0, 1.0],
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| a[i] * b[i]).sum()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalised(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt().max(f64::MIN_POSITIVE);
    a.map(|x| x / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::Geometry;

    fn angle_seen(eye: &Eye, p: [f64; 3]) -> f64 {
        let f = [0, 1, 2].map(|i| eye.look_target[i] - eye.position[i]);
        let d = [0, 1, 2].map(|i| p[i] - eye.position[i]);
        let dot: f64 = (0..3).map(|i| f[i] * d[i]).sum();
        let n = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (dot / (n(f) * n(d))).clamp(-1.0, 1.0).acos()
    }

    #[test]
    fn a_row_of_bodies_fits_the_field_of_view() {
        // Five 4 × 2 × 0.4 m slabs in lanes 3 m apart along −y, as the simulations draw them.
        let slab = Geometry {
            nodes: vec![[0.0, 0.0, 0.0], [4.0, 2.0, 0.4]],
            strips: vec![vec![0, 1]],
        };
        let mut visuals = Vec::new();
        for k in 0..5 {
            visuals.push(Visual::Offset {
                path: format!("world/slab/m{k}"),
                translation: [0.0, -3.0 * k as f64, 0.0],
            });
            visuals.push(Visual::Wireframe {
                path: format!("world/slab/m{k}/body"),
                geometry: slab.clone(),
                color: [0; 4],
                label: None,
            });
        }
        // A visual outside the origin is not framed.
        visuals.push(Visual::Label3D {
            path: "elsewhere/far".into(),
            position: [1e3, 0.0, 0.0],
            text: String::new(),
            color: [0; 4],
        });
        let b = Bounds::of("/world/slab", &visuals).expect("bounds");
        assert_eq!(b.lo, [0.0, -12.0, 0.0]);
        assert_eq!(b.hi, [4.0, 2.0, 0.4]);
        let aspect = 1.3;
        let eye = Eye::framing(&b, aspect);
        // Looking across the row (mostly along x), from above.
        let f = [0, 1, 2].map(|i| eye.look_target[i] - eye.position[i]);
        assert!(f[0].abs() > f[1].abs(), "{f:?}");
        assert!(f[2] < 0.0);
        // Every corner inside the half-angle of the wider (horizontal) field of view, and
        // seen from farther in a narrower view.
        for x in [b.lo[0], b.hi[0]] {
            for y in [b.lo[1], b.hi[1]] {
                for z in [b.lo[2], b.hi[2]] {
                    let a = angle_seen(&eye, [x, y, z]);
                    let half_width = (aspect * (0.5 * FOV_Y).tan()).atan();
                    assert!(a < half_width, "corner {x} {y} {z}: {a}");
                }
            }
        }
        // The row's two ends are seen at angles within a factor of two of each other: neither
        // end recedes to a speck.
        let ends = [[2.0, 1.0, 0.2], [2.0, -11.0, 0.2]].map(|p| {
            let d = [0, 1, 2].map(|i| p[i] - eye.position[i]);
            d.iter().map(|x| x * x).sum::<f64>().sqrt()
        });
        assert!(
            ends[0] / ends[1] < 2.0 && ends[1] / ends[0] < 2.0,
            "{ends:?}"
        );
        let distance = |e: &Eye| {
            (0..3)
                .map(|i| (e.position[i] - e.look_target[i]).powi(2))
                .sum::<f64>()
                .sqrt()
        };
        assert!(distance(&Eye::framing(&b, 0.6)) > 1.5 * distance(&eye));
    }
}
