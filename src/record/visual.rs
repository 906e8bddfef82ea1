//! What a scene draws, independent of Rerun (so scenes are testable without a viewer).

/// Steps of the `phase` timeline per oscillation period of a mode animation.
pub const PHASE_STEPS: usize = 32;

/// RGBA colour.
pub type Color = [u8; 4];

/// Radius of a drawn line in a plane (a chart's series and axes), UI points.
pub const LINE: f32 = 2.0;

/// Radius of a chart's grid lines, UI points: hairlines (the viewer draws a line's colour
/// opaque, so a grid is faint by being thin).
pub const GRID_LINE: f32 = 0.4;

/// A body's drawable geometry: node positions (m) and polylines through them.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Node positions, m.
    pub nodes: Vec<[f64; 3]>,
    /// Polylines as 0-based node index lists.
    pub strips: Vec<Vec<usize>>,
}

impl Geometry {
    /// Geometry of a body: one chain for a beam, the brick edges for a solid.
    pub fn of(model: &crate::fem::FeModel) -> Self {
        let strips = if model.spatial_dim() == 2 {
            vec![(0..model.node_count()).collect()]
        } else {
            straight_strips(&model.nodes, &model.edges)
        };
        Self {
            nodes: model.nodes.clone(),
            strips,
        }
    }

    /// The edges `edges` (pairs of 0-based indices into `nodes`) joined into straight strips:
    /// a part of a mesh drawn on its own.
    pub fn of_edges(nodes: Vec<[f64; 3]>, edges: &[[usize; 2]]) -> Self {
        let strips = straight_strips(&nodes, edges);
        Self { nodes, strips }
    }

    /// The same strips through other node positions.
    pub fn with_nodes(&self, nodes: Vec<[f64; 3]>) -> Self {
        Self {
            nodes,
            strips: self.strips.clone(),
        }
    }
}

/// Joins edges into straight polylines (edges meeting end to end in one direction), so a
/// refined mesh's grid lines are logged as one strip each instead of one per segment.
fn straight_strips(nodes: &[[f64; 3]], edges: &[[usize; 2]]) -> Vec<Vec<usize>> {
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); nodes.len()];
    for (k, e) in edges.iter().enumerate() {
        at[e[0]].push(k);
        at[e[1]].push(k);
    }
    let dir = |a: usize, b: usize| {
        let d = [0, 1, 2].map(|i| nodes[b][i] - nodes[a][i]);
        let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
            .sqrt()
            .max(f64::MIN_POSITIVE);
        d.map(|x| x / n)
    };
    let mut used = vec![false; edges.len()];
    let mut strips = Vec::new();
    for start in 0..edges.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut strip = vec![edges[start][0], edges[start][1]];
        for _ in 0..2 {
            // Extend at the end while an unused edge continues straight on.
            loop {
                let (prev, last) = (strip[strip.len() - 2], strip[strip.len() - 1]);
                let d = dir(prev, last);
                let next = at[last].iter().copied().find(|&k| {
                    let other = if edges[k][0] == last {
                        edges[k][1]
                    } else {
                        edges[k][0]
                    };
                    let e = dir(last, other);
                    !used[k] && d[0] * e[0] + d[1] * e[1] + d[2] * e[2] > 1.0 - 1e-9
                });
                let Some(k) = next else { break };
                used[k] = true;
                strip.push(if edges[k][0] == last {
                    edges[k][1]
                } else {
                    edges[k][0]
                });
            }
            strip.reverse();
        }
        strips.push(strip);
    }
    strips
}

/// One thing to log.
#[derive(Debug, Clone, PartialEq)]
pub enum Visual {
    /// Static geometry (`log_static`), e.g. `world/beam/undeformed`.
    Wireframe {
        /// Entity path.
        path: String,
        /// Lines to draw.
        geometry: Geometry,
        /// Line colour.
        color: Color,
        /// Optional label.
        label: Option<String>,
    },
    /// A mode shape animated over `phase`: nodes + amplitude·sin(2πs/32)·shape.
    Mode {
        /// Entity path (`modes/<set>/<k>`).
        path: String,
        /// Undeformed geometry.
        geometry: Geometry,
        /// Per-node displacement of the mode, already scaled for display (m).
        shape: Vec<[f64; 3]>,
        /// Label, carrying the frequency.
        label: String,
        /// Line colour.
        color: Color,
    },
    /// A static translation of an entity subtree (to lay out several modes side by side).
    Offset {
        /// Entity path.
        path: String,
        /// Translation, m.
        translation: [f64; 3],
    },
    /// A body moving over `sim_time`: one set of node positions per time.
    Trajectory {
        /// Entity path (`world/<body>/<method>/<axes>`).
        path: String,
        /// The strips to draw.
        geometry: Geometry,
        /// Times, s.
        times: Vec<f64>,
        /// Node positions per time, m.
        positions: Vec<Vec<[f64; 3]>>,
        /// Line colour.
        color: Color,
    },
    /// A rigid outline carried by a moving frame over `sim_time` (an undeformed ghost): the
    /// strips logged once in body coordinates, the frame's placement per time as a
    /// transform. A few numbers per time instead of every node's position.
    RigidTrajectory {
        /// Entity path.
        path: String,
        /// The strips to draw, nodes in body coordinates, m.
        geometry: Geometry,
        /// Times, s.
        times: Vec<f64>,
        /// Frame origin per time, m.
        translations: Vec<[f64; 3]>,
        /// Frame orientation per time: the columns of the rotation matrix (body to world).
        rotations: Vec<[[f64; 3]; 3]>,
        /// Line colour.
        color: Color,
    },
    /// A scalar time history over `sim_time` (`plots/...`), sent as columns.
    Series {
        /// Entity path.
        path: String,
        /// Times, s.
        times: Vec<f64>,
        /// Values.
        values: Vec<f64>,
        /// Legend name.
        name: String,
        /// Line colour.
        color: Color,
    },
    /// A floating frame over `sim_time`: origin and axes (columns of A).
    FrameAxes {
        /// Entity path (`world/<body>/frame/<axes>`).
        path: String,
        /// Times, s.
        times: Vec<f64>,
        /// Origin per time, m.
        origins: Vec<[f64; 3]>,
        /// Axis directions per time (ξ, η, ζ as unit vectors).
        axes: Vec<[[f64; 3]; 3]>,
        /// Arrow length, m.
        length: f64,
    },
    /// Labelled points in a plane (`metrics/speed_accuracy`: wall time against error).
    Scatter {
        /// Entity path.
        path: String,
        /// Point positions (x, y).
        points: Vec<[f64; 2]>,
        /// One label per point.
        labels: Vec<String>,
        /// One colour per point.
        colors: Vec<Color>,
    },
    /// Text in a plane, each label centred below its anchor and no marker drawn there (a
    /// chart's ticks, titles and legend).
    Text2D {
        /// Entity path.
        path: String,
        /// Anchors (x, y).
        points: Vec<[f64; 2]>,
        /// One text per anchor.
        labels: Vec<String>,
        /// One colour per text.
        colors: Vec<Color>,
    },
    /// A labelled point in space (static), naming what is drawn beside it.
    Label3D {
        /// Entity path.
        path: String,
        /// Where the label sits, m.
        position: [f64; 3],
        /// The text.
        text: String,
        /// Point and text colour.
        color: Color,
    },
    /// A polyline in a plane (a chart's series), with an optional label.
    Polyline2D {
        /// Entity path.
        path: String,
        /// Vertices (x, y).
        points: Vec<[f64; 2]>,
        /// Line colour.
        color: Color,
        /// Label shown at the line.
        label: Option<String>,
        /// Line radius, UI points: [`LINE`] for a chart's series and axes, [`GRID_LINE`] for
        /// its grid.
        radius: f32,
    },
    /// One series of a grouped bar chart: bars of one colour at given abscissae (several
    /// series under one bar-chart view sit side by side when their abscissae are offset).
    SeriesBars {
        /// Entity path.
        path: String,
        /// Bar positions.
        abscissa: Vec<f64>,
        /// Bar heights.
        values: Vec<f64>,
        /// Bar width (in abscissa units).
        width: f64,
        /// Bar colour.
        color: Color,
    },
}

impl Visual {
    /// The entity path it is logged at.
    pub fn path(&self) -> &str {
        match self {
            Visual::Wireframe { path, .. }
            | Visual::Mode { path, .. }
            | Visual::Offset { path, .. }
            | Visual::Trajectory { path, .. }
            | Visual::RigidTrajectory { path, .. }
            | Visual::Series { path, .. }
            | Visual::FrameAxes { path, .. }
            | Visual::Scatter { path, .. }
            | Visual::Text2D { path, .. }
            | Visual::Label3D { path, .. }
            | Visual::Polyline2D { path, .. }
            | Visual::SeriesBars { path, .. } => path,
        }
    }
}
