//! A viewer layout, converted to a Rerun blueprint by the recorder.

/// Containers and views of the default blueprint.
#[derive(Debug, Clone, PartialEq)]
pub enum Layout {
    /// Side by side, with relative widths.
    Horizontal(Vec<Layout>, Vec<f32>),
    /// Stacked, with relative heights.
    Vertical(Vec<Layout>, Vec<f32>),
    /// Tabs.
    Tabs(Vec<Layout>),
    /// A 3D view.
    Spatial3D {
        /// Tab title.
        name: String,
        /// Origin entity path.
        origin: String,
        /// Entity queries (`$origin/**`, `/world/**`).
        contents: Vec<String>,
    },
    /// The markdown panel.
    Text {
        /// Tab title.
        name: String,
        /// Entity path of the text document.
        origin: String,
    },
    /// A time-series view of everything under `origin`.
    TimeSeries {
        /// Tab title.
        name: String,
        /// Entity path.
        origin: String,
    },
    /// A 2D view (charts drawn as points).
    Spatial2D {
        /// Tab title.
        name: String,
        /// Entity path.
        origin: String,
    },
    /// A bar chart view.
    BarChart {
        /// Tab title.
        name: String,
        /// Entity path.
        origin: String,
        /// Show the legend: for views of several series; a view of one series is named after
        /// it, and its legend would only cover the bars with the entity path.
        legend: bool,
    },
}

impl Layout {
    /// A 3D view showing `origin` and everything below it.
    pub fn view3d(name: &str, origin: &str) -> Self {
        Layout::Spatial3D {
            name: name.into(),
            origin: origin.into(),
            contents: vec!["$origin/**".into()],
        }
    }

    /// The `scene` text panel.
    pub fn scene_text() -> Self {
        Layout::Text {
            name: "scene".into(),
            origin: "/scene".into(),
        }
    }

    /// The benches' sheet: a large chart on the left (`main`: name and origin), a second
    /// chart above the `scene` text as a table on the right; `left` is the left column's
    /// share of the width against the right's 1.
    pub fn bench_charts(main: (&str, &str), second: (&str, &str), left: f32) -> Self {
        let chart = |(name, origin): (&str, &str)| Layout::Spatial2D {
            name: name.into(),
            origin: origin.into(),
        };
        Layout::Horizontal(
            vec![
                chart(main),
                Layout::Vertical(
                    vec![
                        chart(second),
                        Layout::Text {
                            name: "table".into(),
                            origin: "/scene".into(),
                        },
                    ],
                    vec![1.0, 1.0],
                ),
            ],
            vec![left, 1.0],
        )
    }

    /// Origins of the 3D views.
    pub fn spatial_origins(&self) -> Vec<String> {
        match self {
            Layout::Horizontal(v, _) | Layout::Vertical(v, _) | Layout::Tabs(v) => {
                v.iter().flat_map(Layout::spatial_origins).collect()
            }
            Layout::Spatial3D { origin, .. } => vec![origin.clone()],
            Layout::Text { .. }
            | Layout::BarChart { .. }
            | Layout::TimeSeries { .. }
            | Layout::Spatial2D { .. } => vec![],
        }
    }

    /// Entity origins of every view (for tests: each must be logged).
    pub fn origins(&self) -> Vec<String> {
        match self {
            Layout::Horizontal(v, _) | Layout::Vertical(v, _) | Layout::Tabs(v) => {
                v.iter().flat_map(Layout::origins).collect()
            }
            Layout::Spatial3D { origin, .. }
            | Layout::Text { origin, .. }
            | Layout::TimeSeries { origin, .. }
            | Layout::Spatial2D { origin, .. }
            | Layout::BarChart { origin, .. } => vec![origin.clone()],
        }
    }
}
