//! The default blueprint of a recording, logged entity by entity to a blueprint stream: the
//! SDK's builder (`rerun::blueprint::Blueprint`) cannot give a 3D view its starting camera
//! (the view's `EyeControls3D` property), and without one the viewer's default eye sees a row
//! of bodies from one end, so the far bodies are specks.

use super::rerun_sdk::{
    self, RecordingStream, RecordingStreamBuilder,
    blueprint::components::{
        ColumnShare, ContainerKind, Eye3DKind, IncludedContent, LoopMode, PanelState, PlayState,
        QueryExpression, RootContainer, RowShare, ViewClass,
    },
    blueprint_archetypes::{
        ContainerBlueprint, EyeControls3D, PanelBlueprint, PlotLegend, ScalarAxis,
        TimePanelBlueprint, ViewBlueprint, ViewContents, ViewportBlueprint, VisualBounds2D,
    },
    external::re_log_types::{BlueprintActivationCommand, LogMsg},
};

use super::{Bounds, Eye, Layout, layout::split};
use crate::{Error, Result};

/// How the blueprint is built and sent.
pub(crate) struct BlueprintParameters<'a> {
    /// The viewer's area for views, points.
    pub viewport: (f64, f64),
    /// Planar bodies: their "3D" views are 2D views.
    pub planar: bool,
    /// The timeline the time panel plays (looping), if the recording has one.
    pub timeline: Option<&'a str>,
    /// Make it the active blueprint (a file, or the explorer's first recording) besides the
    /// default one (a layout the user changed survives a new recording otherwise).
    pub make_active: bool,
}

/// The viewer's area for views at the default window size (1280 × 800 less the top bar and the
/// collapsed time panel), points: where a view's share of it, and so its aspect, is reckoned
/// (the desktop explorer gives its own, narrower).
pub const VIEWPORT: (f64, f64) = (1280.0, 740.0);

/// Logs `layout` as a blueprint, each 3D view with the camera `eye_for(origin, aspect)` gives
/// (aspect: the view's width over height by the layout's shares), each 2D view showing what
/// `bounds_for(origin)` bounds with a margin, each time-series view the value range
/// `series_range_for(origin)` gives with a margin, and sends it through `rec`.
pub(crate) fn send_blueprint(
    rec: &RecordingStream,
    layout: &Layout,
    eye_for: &dyn Fn(&str, f64) -> Option<Eye>,
    bounds_for: &dyn Fn(&str) -> Option<Bounds>,
    series_range_for: &dyn Fn(&str) -> Option<[f64; 2]>,
    params: &BlueprintParameters,
) -> Result<()> {
    let application_id = rec
        .store_info()
        .map(|info| info.application_id().clone())
        .unwrap_or_else(|| rerun_sdk::ApplicationId::new_or_unknown("flexmodes".to_string()));
    let (bp, storage) = RecordingStreamBuilder::new(application_id)
        .recording_id(uuid::Uuid::new_v4().to_string())
        .blueprint()
        .memory()
        .map_err(rerun_error)?;
    // No log time: two runs give the same blueprint.
    bp.set_log_time_enabled(false);
    bp.set_time_sequence("blueprint", 0);
    let writer = Writer {
        bp: &bp,
        eye_for,
        bounds_for,
        series_range_for,
        planar: params.planar,
    };
    // The viewport's root is a container: a lone view goes into tabs.
    let root = match layout {
        Layout::Horizontal(..) | Layout::Vertical(..) | Layout::Tabs(..) => {
            writer.log(layout, params.viewport, "0")?
        }
        view => writer.log(&Layout::Tabs(vec![view.clone()]), params.viewport, "0")?,
    };
    let root_id = root
        .strip_prefix("container/")
        .and_then(|id| uuid::Uuid::parse_str(id).ok())
        .ok_or_else(|| Error::Rerun {
            step: "blueprint: the root view is not a container",
            source: None,
        })?;
    bp.log(
        "viewport",
        &ViewportBlueprint::new()
            .with_root_container(RootContainer(root_id.into()))
            .with_auto_views(false),
    )
    .map_err(rerun_error)?;
    for panel in ["blueprint_panel", "selection_panel"] {
        bp.log(
            panel,
            &PanelBlueprint::new().with_state(PanelState::Collapsed),
        )
        .map_err(rerun_error)?;
    }
    // Collapsed: the play controls on one line; the views keep the height the streams tree
    // would take.
    let mut time_panel = TimePanelBlueprint::new().with_state(PanelState::Collapsed);
    if let Some(timeline) = params.timeline {
        time_panel = time_panel
            .with_timeline(timeline)
            .with_play_state(PlayState::Playing)
            .with_loop_mode(LoopMode::All);
    }
    bp.log("time_panel", &time_panel).map_err(rerun_error)?;
    bp.flush_blocking()
        .map_err(|e| Error::rerun("blueprint flush", e))?;
    let msgs = storage.take();
    let blueprint_id = msgs
        .iter()
        .find_map(|m| match m {
            LogMsg::SetStoreInfo(info) => Some(info.info.store_id.clone()),
            _ => None,
        })
        .ok_or_else(|| Error::Rerun {
            step: "blueprint: no store info",
            source: None,
        })?;
    rec.send_blueprint(
        msgs,
        BlueprintActivationCommand {
            blueprint_id,
            make_active: params.make_active,
            make_default: true,
        },
    );
    Ok(())
}

/// A failed log call while building the blueprint.
fn rerun_error(e: rerun_sdk::RecordingStreamError) -> Error {
    Error::rerun("blueprint", e)
}

struct Writer<'a> {
    bp: &'a RecordingStream,
    eye_for: &'a dyn Fn(&str, f64) -> Option<Eye>,
    bounds_for: &'a dyn Fn(&str) -> Option<Bounds>,
    series_range_for: &'a dyn Fn(&str) -> Option<[f64; 2]>,
    planar: bool,
}

/// Margin above and below a time-series view's values, as a share of their range (the
/// viewer's own automatic margin).
const MARGIN_SERIES: f64 = 0.05;

/// Margin around a 2D view's contents, as a share of their larger extent (labels sit beside
/// the shapes).
const MARGIN_2D: f64 = 0.12;

/// The id of the container or view at `place` in a layout: a hash of the place and of what
/// the item is (its kind, name and origin; a container's kind), the same in every run.
fn layout_id(place: &str, layout: &Layout) -> uuid::Uuid {
    use std::hash::{Hash, Hasher};
    let what = match layout {
        Layout::Horizontal(..) => "horizontal".to_string(),
        Layout::Vertical(..) => "vertical".to_string(),
        Layout::Tabs(..) => "tabs".to_string(),
        view => format!("{view:?}"),
    };
    let half = |salt: u64| {
        let mut h = std::hash::DefaultHasher::new();
        (salt, place, &what).hash(&mut h);
        h.finish()
    };
    // Shaped as a version-4 uuid, its "random" bytes the hash.
    let mut bytes = [0u8; 16];
    bytes[..8].copy_from_slice(&half(1).to_le_bytes());
    bytes[8..].copy_from_slice(&half(2).to_le_bytes());
    uuid::Builder::from_random_bytes(bytes).into_uuid()
}

impl Writer<'_> {
    /// Logs a container (its children first) or a view given `size` (width, height) of the
    /// viewport; returns its blueprint path (`container/<id>` or `view/<id>`). `place` is its
    /// place in the layout (`0`, `0/2`, …): its id follows from it and from what it shows, so
    /// two recordings of one selection get the same blueprint.
    fn log(&self, layout: &Layout, size: (f64, f64), place: &str) -> Result<String> {
        let id = layout_id(place, layout);
        let container = |kind: ContainerKind,
                         items: &[Layout],
                         sizes: Vec<(f64, f64)>|
         -> Result<ContainerBlueprint> {
            let children = items
                .iter()
                .zip(sizes)
                .enumerate()
                .map(|(k, (item, size))| {
                    self.log(item, size, &format!("{place}/{k}"))
                        .map(|p| IncludedContent(p.as_str().into()))
                })
                .collect::<Result<Vec<_>>>()?;
            Ok(ContainerBlueprint::new(kind).with_contents(children))
        };
        let (width, height) = size;
        let arch = match layout {
            Layout::Horizontal(items, shares) => {
                let sizes = split(width, shares, items.len())
                    .into_iter()
                    .map(|w| (w, height))
                    .collect();
                container(ContainerKind::Horizontal, items, sizes)?
                    .with_col_shares(shares.iter().map(|&s| ColumnShare(s.into())))
            }
            Layout::Vertical(items, shares) => {
                let sizes = split(height, shares, items.len())
                    .into_iter()
                    .map(|h| (width, h))
                    .collect();
                container(ContainerKind::Vertical, items, sizes)?
                    .with_row_shares(shares.iter().map(|&s| RowShare(s.into())))
            }
            Layout::Tabs(items) => container(ContainerKind::Tabs, items, vec![size; items.len()])?,
            view => return self.log_view(view, id, width / height.max(1.0)),
        };
        let path = format!("container/{id}");
        self.bp.log(path.as_str(), &arch).map_err(rerun_error)?;
        Ok(path)
    }

    fn log_view(&self, layout: &Layout, id: uuid::Uuid, aspect: f64) -> Result<String> {
        let path = format!("view/{id}");
        let default_contents = vec!["$origin/**".to_string()];
        let (class, name, origin, contents) = match layout {
            Layout::Spatial3D {
                name,
                origin,
                contents,
            } => (
                if self.planar { "2D" } else { "3D" },
                name,
                origin,
                contents,
            ),
            Layout::Text { name, origin } => ("TextDocument", name, origin, &default_contents),
            Layout::Spatial2D { name, origin } => ("2D", name, origin, &default_contents),
            Layout::TimeSeries { name, origin } => ("TimeSeries", name, origin, &default_contents),
            Layout::BarChart { name, origin, .. } => ("BarChart", name, origin, &default_contents),
            Layout::Horizontal(..) | Layout::Vertical(..) | Layout::Tabs(..) => {
                unreachable!("containers are logged by Writer::log")
            }
        };
        self.bp
            .log(
                format!("{path}/ViewContents").as_str(),
                &ViewContents::new(contents.iter().map(|q| QueryExpression(q.as_str().into()))),
            )
            .map_err(rerun_error)?;
        self.bp
            .log(
                path.as_str(),
                &ViewBlueprint::new(ViewClass(class.into()))
                    .with_display_name(name.as_str())
                    .with_space_origin(origin.as_str()),
            )
            .map_err(rerun_error)?;
        // A bar chart's legend, where shown, sits at the top left: the charts' bars (frequencies,
        // errors by mode number) rise to the right, so the legend covers the fewest there.
        if let Layout::BarChart { legend, .. } = layout {
            let plot_legend = if *legend {
                PlotLegend::new().with_corner(rerun_sdk::blueprint::components::Corner2D::LeftTop)
            } else {
                PlotLegend::new().with_visible(false)
            };
            self.bp
                .log(format!("{path}/PlotLegend").as_str(), &plot_legend)
                .map_err(rerun_error)?;
        }
        // A 2D view shows all it draws (planar bodies are drawn with y up: y flipped), so a beam
        // fits a 1280 × 800 window instead of being cut at its edges.
        if class == "2D"
            && let Some(b) = (self.bounds_for)(origin)
        {
            let m = MARGIN_2D * (b.hi[0] - b.lo[0]).max(b.hi[1] - b.lo[1]).max(1e-9);
            self.bp
                .log(
                    format!("{path}/VisualBounds2D").as_str(),
                    &VisualBounds2D::new(rerun_sdk::blueprint::components::VisualBounds2D::from(
                        rerun_sdk::datatypes::Range2D {
                            x_range: [b.lo[0] - m, b.hi[0] + m].into(),
                            y_range: [-b.hi[1] - m, -b.lo[1] + m].into(),
                        },
                    )),
                )
                .map_err(rerun_error)?;
        }
        // A time-series view gets its value range from the data: left to itself the viewer
        // fits it over the first frames it draws (the plot jumps after a switch).
        if class == "TimeSeries"
            && let Some([lo, hi]) = (self.series_range_for)(origin)
        {
            let m = MARGIN_SERIES * (hi - lo).max(1e-12 * lo.abs().max(hi.abs()).max(1.0));
            self.bp
                .log(
                    format!("{path}/ScalarAxis").as_str(),
                    &ScalarAxis::new().with_range(rerun_sdk::datatypes::Range1D([lo - m, hi + m])),
                )
                .map_err(rerun_error)?;
        }
        if class == "3D"
            && let Some(eye) = (self.eye_for)(origin, aspect)
        {
            let f = |v: [f64; 3]| v.map(|x| x as f32);
            self.bp
                .log(
                    format!("{path}/EyeControls3D").as_str(),
                    &EyeControls3D::new()
                        .with_kind(Eye3DKind::Orbital)
                        .with_position(f(eye.position))
                        .with_look_target(f(eye.look_target))
                        .with_eye_up(f(eye.up)),
                )
                .map_err(rerun_error)?;
        }
        Ok(path)
    }
}
