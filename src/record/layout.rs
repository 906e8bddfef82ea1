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

    /// `views` to the left of the `scene` text panel, three parts to its two: the layout most
    /// scenes share.
    pub fn beside_text(views: Layout) -> Self {
        Layout::Horizontal(vec![views, Layout::scene_text()], vec![3.0, 2.0])
    }

    /// Rows of tabs, one above the other, each as high: for more tabs than one row of a
    /// 1280 × 800 window holds.
    pub fn tab_rows(rows: Vec<Vec<Layout>>) -> Self {
        let shares = vec![1.0; rows.len()];
        Layout::Vertical(rows.into_iter().map(Layout::Tabs).collect(), shares)
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

    /// The size of the view showing `origin` (points, width and height) when the layout fills
    /// `size`; `None` when no view shows it. A tab's view has its container's size.
    pub fn view_size(&self, origin: &str, size: (f64, f64)) -> Option<(f64, f64)> {
        let (width, height) = size;
        match self {
            Layout::Horizontal(items, shares) => items
                .iter()
                .zip(split(width, shares, items.len()))
                .find_map(|(item, w)| item.view_size(origin, (w, height))),
            Layout::Vertical(items, shares) => items
                .iter()
                .zip(split(height, shares, items.len()))
                .find_map(|(item, h)| item.view_size(origin, (width, h))),
            Layout::Tabs(items) => items.iter().find_map(|item| item.view_size(origin, size)),
            view => view.origins().iter().any(|o| o == origin).then_some(size),
        }
    }

    /// The view's tab title; `None` for a container.
    pub fn title(&self) -> Option<&str> {
        match self {
            Layout::Horizontal(..) | Layout::Vertical(..) | Layout::Tabs(..) => None,
            Layout::Spatial3D { name, .. }
            | Layout::Text { name, .. }
            | Layout::TimeSeries { name, .. }
            | Layout::Spatial2D { name, .. }
            | Layout::BarChart { name, .. } => Some(name),
        }
    }

    /// The layout with the tab titles the viewer would cut at `size` (width, height in
    /// points) shortened to fit (`craig_bampton` → `craig_b…`), and each shortened title with
    /// the full one. Titles are never shortened below `MIN_TITLE_CHARS` characters.
    pub fn fit_titles(&self, size: (f64, f64)) -> (Layout, Vec<(String, String)>) {
        let mut short = Vec::new();
        let fitted = self.fitted(size, &mut short);
        (fitted, short)
    }

    fn fitted(&self, size: (f64, f64), short: &mut Vec<(String, String)>) -> Layout {
        let (width, height) = size;
        match self {
            Layout::Horizontal(items, shares) => Layout::Horizontal(
                items
                    .iter()
                    .zip(split(width, shares, items.len()))
                    .map(|(item, w)| item.fitted((w, height), short))
                    .collect(),
                shares.clone(),
            ),
            Layout::Vertical(items, shares) => Layout::Vertical(
                items
                    .iter()
                    .zip(split(height, shares, items.len()))
                    .map(|(item, h)| item.fitted((width, h), short))
                    .collect(),
                shares.clone(),
            ),
            Layout::Tabs(items) => {
                let room = width - items.first().map_or(0.0, Layout::buttons_width);
                let lengths: Vec<usize> = items
                    .iter()
                    .filter_map(|i| i.title().map(|t| t.chars().count()))
                    .collect();
                let needed = |cap: usize| -> f64 {
                    lengths
                        .iter()
                        .map(|&n| title_width(&"x".repeat(n.min(cap)), items.len()))
                        .sum()
                };
                let longest = lengths.iter().copied().max().unwrap_or(0);
                let cap = (MIN_TITLE_CHARS..=longest)
                    .rev()
                    .find(|&cap| needed(cap) <= room)
                    .unwrap_or(MIN_TITLE_CHARS);
                Layout::Tabs(
                    items
                        .iter()
                        .map(|item| match item.title() {
                            Some(t) if t.chars().count() > cap => {
                                let cut: String = t.chars().take(cap - 1).collect();
                                let cut = format!("{}…", cut.trim_end());
                                short.push((cut.clone(), t.to_string()));
                                item.with_title(cut)
                            }
                            Some(_) => item.clone(),
                            None => item.fitted(size, short),
                        })
                        .collect(),
                )
            }
            view => match Layout::Tabs(vec![view.clone()]).fitted(size, short) {
                Layout::Tabs(mut v) if v.len() == 1 => v.remove(0),
                other => other,
            },
        }
    }

    /// The view with its title replaced (a container unchanged).
    fn with_title(&self, title: String) -> Layout {
        let mut out = self.clone();
        match &mut out {
            Layout::Horizontal(..) | Layout::Vertical(..) | Layout::Tabs(..) => {}
            Layout::Spatial3D { name, .. }
            | Layout::Text { name, .. }
            | Layout::TimeSeries { name, .. }
            | Layout::Spatial2D { name, .. }
            | Layout::BarChart { name, .. } => *name = title,
        }
        out
    }

    /// What the view's title-bar buttons take, points: help, visibility and maximise, and a
    /// time series' play arrow; a container's first item's.
    fn buttons_width(&self) -> f64 {
        match self {
            Layout::Horizontal(v, _) | Layout::Vertical(v, _) | Layout::Tabs(v) => {
                v.first().map_or(0.0, Layout::buttons_width)
            }
            Layout::TimeSeries { .. } => 4.0 * TITLE_BAR_BUTTON,
            _ => 3.0 * TITLE_BAR_BUTTON,
        }
    }

    /// The tab titles the viewer would cut when the layout fills `size` (width, height in
    /// points), by the estimate of `title_width` and `TITLE_BAR_BUTTON`: a lone view's
    /// title shares its width with the view's buttons, the titles of a tabs container share
    /// the container's width with the buttons of its shown view.
    pub fn cut_titles(&self, size: (f64, f64)) -> Vec<String> {
        let (width, height) = size;
        match self {
            Layout::Horizontal(items, shares) => items
                .iter()
                .zip(split(width, shares, items.len()))
                .flat_map(|(item, w)| item.cut_titles((w, height)))
                .collect(),
            Layout::Vertical(items, shares) => items
                .iter()
                .zip(split(height, shares, items.len()))
                .flat_map(|(item, h)| item.cut_titles((width, h)))
                .collect(),
            Layout::Tabs(items) => {
                // The buttons of the view shown (the first).
                let mut used = items.first().map_or(0.0, Layout::buttons_width);
                let mut cut = Vec::new();
                let tabs = items.len();
                for item in items {
                    match item.title() {
                        Some(t) => {
                            used += title_width(t, tabs);
                            if used > width {
                                cut.push(t.to_string());
                            }
                        }
                        None => cut.extend(item.cut_titles(size)),
                    }
                }
                cut
            }
            view => Layout::Tabs(vec![view.clone()]).cut_titles(size),
        }
    }
}

/// Tab titles are shortened to no fewer characters than this (the ellipsis included).
pub const MIN_TITLE_CHARS: usize = 5;

/// What one of a view's title-bar buttons takes, points (measured on the explorer's
/// screenshots at 1 280 × 800).
pub const TITLE_BAR_BUTTON: f64 = 25.0;

/// The width of a tab with title `title`, points, among `tabs` tabs: its characters at 7.5
/// points (the viewer's proportional font, 12 points) and the tab's icon and padding, 24
/// points for a lone view and 36 in a group (measured on the explorer's screenshots: a lone
/// two-letter title fits a 114-point bar chart; eight five-character tabs need 590 points).
pub fn title_width(title: &str, tabs: usize) -> f64 {
    let padding = if tabs > 1 { 36.0 } else { 24.0 };
    padding + 7.5 * title.chars().count() as f64
}

/// The parts of `size` that `shares` give, one per item (equal parts without shares).
pub(super) fn split(size: f64, shares: &[f32], items: usize) -> Vec<f64> {
    let shares: Vec<f64> = (0..items)
        .map(|i| shares.get(i).map_or(1.0, |&s| f64::from(s).max(0.0)))
        .collect();
    let total = shares.iter().sum::<f64>().max(f64::MIN_POSITIVE);
    shares.iter().map(|s| size * s / total).collect()
}
