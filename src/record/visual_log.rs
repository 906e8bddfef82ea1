//! Each [`Visual`] logged to a Rerun recording stream: wireframes and mode animations as
//! line strips over the `phase` timeline, trajectories over `sim_time`, frames, series,
//! labelled points and text, charts' lines and bars; Rerun's errors named by the step.

use super::rerun_sdk::{self, RecordingStream};
use super::{Color, Geometry, PHASE_STEPS, Visual};
use crate::{Error, Result};

fn strips(g: &Geometry, nodes: &[[f64; 3]]) -> Vec<Vec<[f32; 3]>> {
    g.strips
        .iter()
        .map(|s| {
            s.iter()
                .map(|&i| nodes[i].map(|x| x as f32))
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Line strips with one colour, radius and optional label, as 3D strips or, for a planar
/// body, as 2D strips with y pointing up (2D views point y down).
struct Lines {
    strips: Vec<Vec<[f32; 3]>>,
    color: rerun_sdk::Color,
    radius: f32,
    label: Option<String>,
}

/// The strips of every frame of an animation, one row per time of `time`, in one
/// `send_columns` call (the style is logged apart, once).
fn send_strip_frames(
    rec: &RecordingStream,
    path: &str,
    time: rerun_sdk::TimeColumn,
    frames: Vec<Vec<Vec<[f32; 3]>>>,
    planar: bool,
) -> Result<()> {
    let lengths: Vec<usize> = frames.iter().map(Vec::len).collect();
    let all = frames.into_iter().flatten();
    if planar {
        let flat = all.map(|s| s.into_iter().map(|p| [p[0], -p[1]]).collect::<Vec<_>>());
        rec.send_columns(
            path,
            [time],
            rerun_sdk::LineStrips2D::update_fields()
                .with_strips(flat)
                .columns(lengths)
                .or_rerun()?,
        )
        .or_rerun()?;
    } else {
        rec.send_columns(
            path,
            [time],
            rerun_sdk::LineStrips3D::update_fields()
                .with_strips(all)
                .columns(lengths)
                .or_rerun()?,
        )
        .or_rerun()?;
    }
    Ok(())
}

impl Lines {
    /// Colour, radius and label without strips (logged once, static, beside strips sent as
    /// columns).
    fn style(self, planar: bool) -> Box<dyn rerun_sdk::AsComponents> {
        self.build(planar, false)
    }

    /// Strips with their colour, radius and label.
    fn archetype(self, planar: bool) -> Box<dyn rerun_sdk::AsComponents> {
        self.build(planar, true)
    }

    fn build(self, planar: bool, with_strips: bool) -> Box<dyn rerun_sdk::AsComponents> {
        if planar {
            let mut a = rerun_sdk::LineStrips2D::update_fields()
                .with_colors([self.color])
                .with_radii([self.radius]);
            if with_strips {
                a = a.with_strips(
                    self.strips
                        .iter()
                        .map(|s| s.iter().map(|p| [p[0], -p[1]]).collect::<Vec<_>>()),
                );
            }
            if let Some(l) = self.label {
                a = a.with_labels([l]);
            }
            Box::new(a)
        } else {
            let mut a = rerun_sdk::LineStrips3D::update_fields()
                .with_colors([self.color])
                .with_radii([self.radius]);
            if with_strips {
                a = a.with_strips(self.strips);
            }
            if let Some(l) = self.label {
                a = a.with_labels([l]);
            }
            Box::new(a)
        }
    }
}

fn radius(g: &Geometry) -> f32 {
    let mut ext = 0.0f64;
    for d in 0..3 {
        let lo = g.nodes.iter().map(|p| p[d]).fold(f64::INFINITY, f64::min);
        let hi = g
            .nodes
            .iter()
            .map(|p| p[d])
            .fold(f64::NEG_INFINITY, f64::max);
        ext = ext.max(hi - lo);
    }
    (ext * 0.004).max(1e-4) as f32
}

fn color(c: [u8; 4]) -> rerun_sdk::Color {
    rerun_sdk::Color::from_unmultiplied_rgba(c[0], c[1], c[2], c[3])
}

pub(super) fn log_visual(rec: &RecordingStream, v: &Visual, planar: bool) -> Result<()> {
    match v {
        Visual::Wireframe {
            path,
            geometry,
            color: c,
            label,
        } => log_wireframe(rec, path, geometry, (*c, label), planar)?,
        Visual::Mode {
            path,
            geometry,
            shape,
            label,
            color: c,
        } => log_mode(rec, path, geometry, shape, label, *c, planar)?,
        Visual::Offset { path, translation } => {
            rec.log_static(
                path.as_str(),
                &rerun_sdk::Transform3D::from_translation(if planar {
                    [translation[0] as f32, -translation[1] as f32, 0.0]
                } else {
                    translation.map(|x| x as f32)
                }),
            )
            .or_rerun()?;
        }
        Visual::Trajectory {
            path,
            geometry,
            times,
            positions,
            color: c,
        } => log_trajectory(rec, path, geometry, times, positions, *c)?,
        Visual::RigidTrajectory {
            path,
            geometry,
            times,
            translations,
            rotations,
            color: c,
        } => log_rigid_trajectory(rec, path, geometry, times, translations, rotations, *c)?,
        Visual::Series {
            path,
            times,
            values,
            name,
            color: c,
        } => log_series(rec, path, times, values, (name, *c))?,
        Visual::FrameAxes {
            path,
            times,
            origins,
            axes,
            length,
        } => log_frame_axes(rec, path, times, origins, axes, *length)?,
        Visual::Label3D {
            path,
            position,
            text,
            color: c,
        } => log_label(rec, path, position, text, *c)?,
        Visual::Scatter {
            path,
            points,
            labels,
            colors,
        } => {
            rec.log_static(path.as_str(), &labelled_points(points, labels, colors, 6.0))
                .or_rerun()?;
        }
        Visual::Text2D {
            path,
            points,
            labels,
            colors,
        } => {
            // Radius 0: the viewer draws the labels at their anchors and no point there.
            rec.log_static(
                path.as_str(),
                &labelled_points(points, labels, colors, 0.0).with_show_labels(true),
            )
            .or_rerun()?;
        }
        Visual::Polyline2D {
            path,
            points,
            color: c,
            label,
            radius,
        } => log_polyline(rec, path, points, (*c, label, *radius))?,
        Visual::SeriesBars {
            path,
            abscissa,
            values,
            width,
            color: c,
        } => log_bars(rec, path, abscissa, values, (*width, *c))?,
    }
    Ok(())
}

/// A mode shape: the undeformed body in grey, then the deformed one over a phase cycle.
fn log_mode(
    rec: &RecordingStream,
    path: &str,
    geometry: &Geometry,
    shape: &[[f64; 3]],
    label: &str,
    c: Color,
    planar: bool,
) -> Result<()> {
    if shape.len() != geometry.nodes.len() {
        return Err(Error::MismatchedSeries {
            path: path.into(),
            what: "nodal displacements for its nodes",
            expected: geometry.nodes.len(),
            found: shape.len(),
        });
    }
    let r = radius(geometry);
    let undeformed = Lines {
        strips: strips(geometry, &geometry.nodes),
        color: rerun_sdk::Color::from_unmultiplied_rgba(150, 150, 150, 120),
        radius: r * 0.5,
        label: None,
    };
    rec.log_static(
        format!("{path}/undeformed"),
        undeformed.archetype(planar).as_ref(),
    )
    .or_rerun()?;
    // Colour, radius and label once; the strips of all phase steps in one call.
    let frames: Vec<Vec<Vec<[f32; 3]>>> = (0..PHASE_STEPS)
        .map(|s| {
            let a = (2.0 * std::f64::consts::PI * s as f64 / PHASE_STEPS as f64).sin();
            let nodes: Vec<[f64; 3]> = geometry
                .nodes
                .iter()
                .zip(shape)
                .map(|(p, u)| [p[0] + a * u[0], p[1] + a * u[1], p[2] + a * u[2]])
                .collect();
            strips(geometry, &nodes)
        })
        .collect();
    // A planar shape's name hangs below the lowest point it reaches over the cycle (the
    // viewer draws a strip's label on the strip, over the curve it names); a 3D one keeps
    // the strip's own label.
    let style = Lines {
        strips: Vec::new(),
        color: color(c),
        radius: r,
        label: (!planar).then(|| label.to_string()),
    };
    rec.log_static(path, style.style(planar).as_ref())
        .or_rerun()?;
    if planar {
        let undeformed = geometry.nodes.iter().map(|p| [p[0] as f32, p[1] as f32]);
        let deformed = frames.iter().flatten().flatten().map(|p| [p[0], p[1]]);
        let (mut x0, mut x1, mut y0) = (f32::INFINITY, f32::NEG_INFINITY, f32::INFINITY);
        for p in undeformed.chain(deformed) {
            x0 = x0.min(p[0]);
            x1 = x1.max(p[0]);
            y0 = y0.min(p[1]);
        }
        // 2D views point y down: the lowest point is at −y0; the label's box hangs below
        // its anchor, which clears the line by its width.
        let anchor = [0.5 * f64::from(x0 + x1), f64::from(-y0 + 2.0 * r)];
        rec.log_static(
            format!("{path}/label"),
            &labelled_points(&[anchor], &[label.to_string()], &[c], 0.0).with_show_labels(true),
        )
        .or_rerun()?;
    }
    send_strip_frames(
        rec,
        path,
        rerun_sdk::TimeColumn::new_sequence("phase", 0..PHASE_STEPS as i64),
        frames,
        planar,
    )?;
    Ok(())
}

/// Width of a deformable body's drawn lines against a rigid outline's (its undeformed ghost,
/// a link): where the two coincide, at rest (a simulation's first instant), the body's colour
/// still shows around the grey ghost instead of vanishing under it for that frame.
const DEFORMED_LINE_WIDTH: f32 = 1.6;

/// A deformable body's drawn history over simulated time.
fn log_trajectory(
    rec: &RecordingStream,
    path: &str,
    geometry: &Geometry,
    times: &[f64],
    positions: &[Vec<[f64; 3]>],
    c: Color,
) -> Result<()> {
    let r = DEFORMED_LINE_WIDTH
        * positions
            .first()
            .map(|p| radius(&geometry.with_nodes(p.clone())))
            .unwrap_or(1e-3);
    let style = Lines {
        strips: Vec::new(),
        color: color(c),
        radius: r,
        label: None,
    };
    rec.log_static(path, style.style(false).as_ref())
        .or_rerun()?;
    let n = times.len().min(positions.len());
    send_strip_frames(
        rec,
        path,
        rerun_sdk::TimeColumn::new_duration_secs("sim_time", times[..n].iter().copied()),
        positions[..n]
            .iter()
            .map(|nodes| strips(geometry, nodes))
            .collect(),
        false,
    )?;
    Ok(())
}

/// A rigid body's drawing, placed over simulated time by one transform per instant.
fn log_rigid_trajectory(
    rec: &RecordingStream,
    path: &str,
    geometry: &Geometry,
    times: &[f64],
    translations: &[[f64; 3]],
    rotations: &[[[f64; 3]; 3]],
    c: Color,
) -> Result<()> {
    let lines = Lines {
        strips: strips(geometry, &geometry.nodes),
        color: color(c),
        radius: radius(geometry),
        label: None,
    };
    rec.log_static(path, lines.archetype(false).as_ref())
        .or_rerun()?;
    let n = times.len().min(translations.len()).min(rotations.len());
    rec.send_columns(
        path,
        [rerun_sdk::TimeColumn::new_duration_secs(
            "sim_time",
            times[..n].iter().copied(),
        )],
        rerun_sdk::Transform3D::update_fields()
            .with_many_translation(translations[..n].iter().map(|t| t.map(|x| x as f32)))
            .with_many_mat3x3(rotations[..n].iter().map(|r| {
                rerun_sdk::datatypes::Mat3x3::from([
                    r[0].map(|x| x as f32),
                    r[1].map(|x| x as f32),
                    r[2].map(|x| x as f32),
                ])
            }))
            .columns_of_unit_batches()
            .or_rerun()?,
    )
    .or_rerun()?;
    Ok(())
}

/// A frame's axes over simulated time, red, green and blue for x, y and z.
fn log_frame_axes(
    rec: &RecordingStream,
    path: &str,
    times: &[f64],
    origins: &[[f64; 3]],
    axes: &[[[f64; 3]; 3]],
    length: f64,
) -> Result<()> {
    let colors = [
        rerun_sdk::Color::from_rgb(230, 60, 60),
        rerun_sdk::Color::from_rgb(60, 200, 60),
        rerun_sdk::Color::from_rgb(60, 110, 240),
    ];
    for (what, found) in [
        ("frame origins for its times", origins.len()),
        ("axis triads for its times", axes.len()),
    ] {
        if found != times.len() {
            return Err(Error::MismatchedSeries {
                path: path.into(),
                what,
                expected: times.len(),
                found,
            });
        }
    }
    for ((t, o), a) in times.iter().zip(origins).zip(axes) {
        rec.set_duration_secs("sim_time", *t);
        let o32 = o.map(|x| x as f32);
        rec.log(
            path,
            &rerun_sdk::Arrows3D::from_vectors(a.map(|v| v.map(|x| (x * length) as f32)))
                .with_origins([o32, o32, o32])
                .with_colors(colors),
        )
        .or_rerun()?;
    }
    rec.reset_time();
    Ok(())
}

/// Rerun's errors as [`Error::Rerun`], naming the step that failed: logging or serialising.
/// (The error enum is `flexmodes-core`'s, which knows nothing of Rerun: the conversion lives
/// here, with the one recorder.)
pub(super) trait OrRerun<T> {
    fn or_rerun(self) -> Result<T>;
}

impl<T> OrRerun<T> for std::result::Result<T, rerun_sdk::RecordingStreamError> {
    fn or_rerun(self) -> Result<T> {
        self.map_err(|e| Error::rerun("log", e))
    }
}

impl<T> OrRerun<T> for std::result::Result<T, rerun_sdk::SerializationError> {
    fn or_rerun(self) -> Result<T> {
        self.map_err(|e| Error::rerun("serialise", e))
    }
}

/// Points in a plane with a label and colour each, `radius` UI points across.
fn labelled_points(
    points: &[[f64; 2]],
    labels: &[String],
    colors: &[Color],
    radius: f32,
) -> rerun_sdk::Points2D {
    rerun_sdk::Points2D::new(points.iter().map(|p| [p[0] as f32, p[1] as f32]))
        .with_labels(labels.to_vec())
        .with_colors(colors.iter().map(|c| color(*c)))
        .with_radii([rerun_sdk::Radius::new_ui_points(radius)])
}

/// A time series over `sim_time`: its style once, its values as columns.
fn log_series(
    rec: &RecordingStream,
    path: &str,
    times: &[f64],
    values: &[f64],
    (name, c): (&str, Color),
) -> Result<()> {
    rec.log_static(
        path,
        &rerun_sdk::SeriesLines::new()
            .with_colors([color(c)])
            .with_names([name.to_string()]),
    )
    .or_rerun()?;
    rec.send_columns(
        path,
        [rerun_sdk::TimeColumn::new_duration_secs(
            "sim_time",
            times.iter().copied(),
        )],
        rerun_sdk::Scalars::new(values.iter().copied())
            .columns_of_unit_batches()
            .or_rerun()?,
    )
    .or_rerun()?;
    Ok(())
}

/// A 2-D line strip of `radius` UI points, labelled when `label` is set.
fn log_polyline(
    rec: &RecordingStream,
    path: &str,
    points: &[[f64; 2]],
    (c, label, radius): (Color, &Option<String>, f32),
) -> Result<()> {
    let mut strips = rerun_sdk::LineStrips2D::new([points
        .iter()
        .map(|p| [p[0] as f32, p[1] as f32])
        .collect::<Vec<_>>()])
    .with_colors([color(c)])
    .with_radii([rerun_sdk::Radius::new_ui_points(radius)]);
    if let Some(l) = label {
        strips = strips.with_labels([l.clone()]);
    }
    rec.log_static(path, &strips).or_rerun()?;
    Ok(())
}

/// Bars at `abscissa`, `width` wide.
fn log_bars(
    rec: &RecordingStream,
    path: &str,
    abscissa: &[f64],
    values: &[f64],
    (width, c): (f64, Color),
) -> Result<()> {
    rec.log_static(
        path,
        &rerun_sdk::BarChart::new(values.to_vec())
            .with_abscissa(abscissa.to_vec())
            .with_widths([width as f32])
            .with_color(color(c)),
    )
    .or_rerun()?;
    Ok(())
}

/// A body's outline, once.
fn log_wireframe(
    rec: &RecordingStream,
    path: &str,
    geometry: &Geometry,
    (c, label): (Color, &Option<String>),
    planar: bool,
) -> Result<()> {
    let lines = Lines {
        strips: strips(geometry, &geometry.nodes),
        color: color(c),
        radius: radius(geometry),
        label: label.clone(),
    };
    rec.log_static(path, lines.archetype(planar).as_ref())
        .or_rerun()?;
    Ok(())
}

/// A labelled point in 3-D, once.
fn log_label(
    rec: &RecordingStream,
    path: &str,
    position: &[f64; 3],
    text: &str,
    c: Color,
) -> Result<()> {
    rec.log_static(
        path,
        &rerun_sdk::Points3D::new([position.map(|x| x as f32)])
            .with_labels([text.to_string()])
            .with_colors([color(c)])
            .with_radii([rerun_sdk::Radius::new_ui_points(4.0)]),
    )
    .or_rerun()?;
    Ok(())
}
