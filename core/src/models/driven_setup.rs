//! What a driven body's runs are set up from: the drive (the rigid interface the frame
//! turns), the prescribed motion, the preloaded stiffness' agreement with it, the outputs and
//! their mean-axis view, the pinned rings, and the basis columns the frame leaves free.

use nalgebra::{Unit, Vector3};

use super::{BodyInterfaces, DrivenBodyParameters};
use crate::{
    Result,
    analysis::MeanAxisView,
    body_file::{ImportedBody, InterfaceKind, Preload},
    dynamics::{AxisKind, DrivenFrameBody, Driving, DynamicsError, PinnedRing, Shake, SpinUp},
    error::{DofSetName, DofSetProblem},
    fem::{FeModel, NodeIndex},
    reduction::{Basis, ColumnKind, ReductionError, RigidInterface},
};

/// The drive: the one rigid interface `item` names (`rbe2:SET` or an rbe2 interface of the
/// body file).
pub(super) fn drive_interface(
    body: &ImportedBody,
    item: &str,
    interfaces: &BodyInterfaces,
) -> Result<RigidInterface> {
    let (_, sets) = body.boundary_with_interfaces(&[item.to_string()])?;
    match sets.first() {
        Some(set) if set.kind == InterfaceKind::Rbe2 && sets.len() == 1 => Ok(interfaces
            .rigid
            .iter()
            .find(|i| i.name == set.name)
            .cloned()
            .expect("named above")),
        _ => Err(ReductionError::InvalidDofSet {
            set: DofSetName::Given(item.into()),
            problem: DofSetProblem::DriveNotRigid,
        }
        .into()),
    }
}

/// The full body `full` (turning about `axis` through `origin`, the DOF `ring` clamped)
/// given the dynamic stiffening of `body`'s preloaded stiffness when `stiffening` asks for it
/// and the body has one, checked against the spin ([`check_preload`]). Returns whether it
/// was given.
pub(super) fn apply_preload(
    body: &ImportedBody,
    full: &mut DrivenFrameBody,
    stiffening: bool,
    (axis, origin): (Unit<Vector3<f64>>, [f64; 3]),
    ring: &[usize],
) -> Result<bool> {
    match (&body.preload, stiffening) {
        (Some(preload), true) => {
            check_preload(preload, axis, origin, ring, body.model.size())?;
            full.set_centrifugal_stiffening(&preload.rate_squared)?;
            Ok(true)
        }
        _ => Ok(false),
    }
}

/// Share of the fitted radius, beside three times the fit's RMS residual, by which a drive's
/// ring centre may miss the preload's axis and still count as coaxial with it.
pub const COAXIAL_RADIUS_SHARE: f64 = 0.02;

/// A point of the spin axis (length unit) and where it came from (`--axis-point`, the
/// drive's master, …).
pub(super) type AxisPoint = ([f64; 3], &'static str);

/// The point of the spin axis the frame turns about, and where it came from: `asked` when
/// given (`--axis-point`); else, when the body's preload (with `stiffening`) was spun about
/// an axis parallel to `axis`, its axis, provided the drive's ring is coaxial with it (the
/// centre of the circle fitted to the ring's nodes in the plane across the axis within
/// [`COAXIAL_RADIUS_SHARE`] of its radius plus three RMS residuals of the fit; otherwise
/// [`DynamicsError::DriveOffPreloadAxis`]): an uneven mesh's ring centroid is not its
/// hole's centre. Without a preload, the drive's master.
pub(super) fn spin_axis_point(
    body: &ImportedBody,
    drive: &RigidInterface,
    axis: Unit<Vector3<f64>>,
    asked: Option<[f64; 3]>,
    stiffening: bool,
) -> Result<AxisPoint> {
    if let Some(p) = asked {
        return Ok((p, "--axis-point"));
    }
    let Some(preload) = body.preload.as_ref().filter(|_| stiffening) else {
        return Ok((drive.master, "the drive's master"));
    };
    let a = preload.load.axis.into_inner();
    let e = axis.into_inner();
    if a.cross(&e).norm() > 1e-6 {
        // Another axis: check_preload names the angle.
        return Ok((drive.master, "the drive's master"));
    }
    let points: Vec<Vector3<f64>> = drive
        .nodes
        .iter()
        .map(|&n| Vector3::from(body.model.nodes[n - 1]))
        .collect();
    let p0 = Vector3::from(preload.load.point);
    let (centre, radius, rms) = fitted_circle(&points, a);
    let d = centre - p0;
    let distance = (d - a * a.dot(&d)).norm();
    let tolerance = COAXIAL_RADIUS_SHARE * radius + 3.0 * rms;
    if distance <= tolerance {
        // The preload's axis, at the ring's station along it.
        let on_axis = p0 + a * a.dot(&d);
        return Ok((
            on_axis.into(),
            "the [preload]'s axis (the drive's ring is coaxial)",
        ));
    }
    Err(DynamicsError::DriveOffPreloadAxis {
        drive: drive.name.clone(),
        distance,
        tolerance,
        point: preload.load.point,
    }
    .into())
}

/// The circle fitted to `points` in the plane across `axis` (algebraic least squares,
/// $x^2 + y^2 = 2ax + 2by + c$): its centre (at the points' mean station along the axis),
/// radius and the RMS of the points' distances from it. Points on a line or fewer than
/// three give their centroid, radius 0 and their RMS distance from it.
fn fitted_circle(points: &[Vector3<f64>], axis: Vector3<f64>) -> (Vector3<f64>, f64, f64) {
    let n = points.len().max(1) as f64;
    let mean = points.iter().fold(Vector3::zeros(), |s, p| s + p) / n;
    let helper = if axis.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let u = axis.cross(&helper).normalize();
    let v = axis.cross(&u);
    let xy: Vec<(f64, f64)> = points
        .iter()
        .map(|p| ((p - mean).dot(&u), (p - mean).dot(&v)))
        .collect();
    let mut ata = nalgebra::Matrix3::<f64>::zeros();
    let mut atb = Vector3::<f64>::zeros();
    for &(x, y) in &xy {
        let row = Vector3::new(2.0 * x, 2.0 * y, 1.0);
        ata += row * row.transpose();
        atb += row * (x * x + y * y);
    }
    let spread = |c: Vector3<f64>, r: f64| {
        (points
            .iter()
            .map(|p| {
                let d = p - c;
                let radial = (d - axis * axis.dot(&d)).norm();
                (radial - r).powi(2)
            })
            .sum::<f64>()
            / n)
            .sqrt()
    };
    match (points.len() >= 3).then(|| ata.lu().solve(&atb)).flatten() {
        Some(s) if s.iter().all(|x| x.is_finite()) && s.z + s.x * s.x + s.y * s.y > 0.0 => {
            let centre = mean + u * s.x + v * s.y;
            let radius = (s.z + s.x * s.x + s.y * s.y).sqrt();
            (centre, radius, spread(centre, radius))
        }
        _ => (mean, 0.0, spread(mean, 0.0)),
    }
}

/// A preloaded stiffness applies to a spin about its own axis with the drive's ring held as
/// its static step held it: the axes parallel (1e-6 rad), the frame's origin on its axis
/// (1e-6 of the body's size), its held DOF the ring's.
fn check_preload(
    preload: &Preload,
    axis: Unit<Vector3<f64>>,
    origin: [f64; 3],
    ring: &[usize],
    size: f64,
) -> Result<()> {
    let (a, e) = (preload.load.axis.into_inner(), axis.into_inner());
    let angle = a.cross(&e).norm().atan2(a.dot(&e).abs());
    let mismatch = |angle_rad, offset, held| {
        Err(DynamicsError::PreloadMismatch {
            angle_rad,
            offset,
            held,
        }
        .into())
    };
    if angle > 1e-6 {
        return mismatch(Some(angle), None, None);
    }
    let d = Vector3::from(origin) - Vector3::from(preload.load.point);
    let offset = (d - a * a.dot(&d)).norm();
    if offset > 1e-6 * size.max(f64::MIN_POSITIVE) {
        return mismatch(None, Some(offset), None);
    }
    let mut held = preload.held.clone();
    held.sort_unstable();
    let mut clamped = ring.to_vec();
    clamped.sort_unstable();
    if held != clamped {
        let both = held
            .iter()
            .filter(|d| clamped.binary_search(d).is_ok())
            .count();
        return mismatch(None, None, Some((held.len(), clamped.len(), both)));
    }
    Ok(())
}

/// The prescribed motion of the parameters, checked: a nonzero spin axis, a positive ramp
/// (s) and step (s), gravity and shaking in the body's length unit.
pub(super) fn driving_of(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
) -> Result<Driving> {
    let axis = Unit::try_new(Vector3::from(parameters.axis), 1e-12).ok_or(
        DynamicsError::ZeroDirection {
            setting: "spin axis",
        },
    )?;
    if parameters.ramp.is_nan() || parameters.ramp <= 0.0 {
        return Err(DynamicsError::NotPositive {
            setting: "ramp time (s)",
            value: parameters.ramp,
        }
        .into());
    }
    if parameters.integration.step.is_nan() || parameters.integration.step <= 0.0 {
        return Err(DynamicsError::InvalidStep {
            step: parameters.integration.step,
        }
        .into());
    }
    let gravity = match parameters.gravity {
        Some(g) => Vector3::from(g) / body.units.metres_per_length()?,
        None => Vector3::zeros(),
    };
    let shake = match parameters.shake {
        Some((direction, amplitude, frequency)) => Some(Shake {
            direction: Unit::try_new(Vector3::from(direction), 1e-12).ok_or(
                DynamicsError::ZeroDirection {
                    setting: "shaking direction",
                },
            )?,
            amplitude: amplitude / body.units.metres_per_length()?,
            frequency,
        }),
        None => None,
    };
    Ok(Driving {
        spin: SpinUp {
            axis,
            rate: parameters.rate,
            ramp: parameters.ramp,
        },
        shake,
        gravity,
    })
}

/// The outputs asked for; by default every node set but the drive and the pinned rings, or,
/// when there is none, the node farthest from the drive's master (`node:N`, 1-based).
pub(super) fn output_names(
    body: &ImportedBody,
    parameters: &DrivenBodyParameters,
    drive: &RigidInterface,
    pinned_names: &[&str],
) -> Vec<String> {
    if !parameters.outputs.is_empty() {
        return parameters.outputs.clone();
    }
    let sets: Vec<String> = body
        .node_sets
        .keys()
        .filter(|k| **k != drive.name && !pinned_names.contains(&k.as_str()))
        .cloned()
        .collect();
    if !sets.is_empty() {
        return sets;
    }
    let model = &body.model;
    let far = (0..model.node_count())
        .max_by(|&a, &b| {
            let d = |j: usize| {
                let p = model.nodes[j];
                (0..3)
                    .map(|k| (p[k] - drive.master[k]).powi(2))
                    .sum::<f64>()
            };
            d(a).total_cmp(&d(b))
        })
        .unwrap_or(0);
    vec![format!("node:{}", NodeIndex(far).number())]
}

/// The nodes (1-based) of output `name`: a node set, or `node:N`.
pub(super) fn output_nodes(body: &ImportedBody, name: &str) -> Result<Vec<usize>> {
    let unknown = || DynamicsError::UnknownOutput {
        name: name.into(),
        known: crate::error::Name::all(body.node_sets.keys()),
    };
    Ok(match name.strip_prefix("node:") {
        Some(number) => vec![number.parse::<usize>().map_err(|_| unknown())?],
        None => body.node_sets.get(name).ok_or_else(unknown)?.clone(),
    })
}

/// The histories' mean-axis view and, per output set, its rigid rows' mean (`None` on
/// nodal-fixed axes; principal axes are not offered for a driven body).
#[allow(clippy::type_complexity)]
pub(super) fn mean_axes_of(
    model: &FeModel,
    axes: AxisKind,
    outputs: &[Vec<usize>],
) -> Result<Option<(MeanAxisView, Vec<Vec<Vec<f64>>>)>> {
    match axes {
        AxisKind::NodalFixed => Ok(None),
        AxisKind::Mean => {
            let view = MeanAxisView::of(model)?;
            let rows = outputs.iter().map(|dofs| view.mean_rows(dofs)).collect();
            Ok(Some((view, rows)))
        }
        AxisKind::Principal => Err(DynamicsError::AxesNotOffered { axes: "principal" }.into()),
    }
}

/// Pinned rings: their masters' translations held in the frame, rotations free.
pub(super) fn pinned_rings(
    model: &FeModel,
    interfaces: &BodyInterfaces,
    pinned_items: &[String],
) -> Result<Vec<PinnedRing>> {
    let mut pins = Vec::new();
    for item in pinned_items {
        let name = item.split_once(':').map_or(item.as_str(), |(_, n)| n);
        let interface = interfaces
            .rigid
            .iter()
            .find(|i| i.name == name)
            .ok_or_else(|| ReductionError::InvalidDofSet {
                set: DofSetName::Given(item.into()),
                problem: DofSetProblem::PinNotRigid,
            })?;
        let rows = interface.rigid_motions(model)?;
        pins.push(PinnedRing {
            name: interface.name.clone(),
            dofs: rows.iter().map(|(d, _)| *d).collect(),
            rows: rows.iter().map(|(_, r)| [r[3], r[4], r[5]]).collect(),
        });
    }
    Ok(pins)
}

/// The columns of a basis the driven frame leaves free: all but the drive's unit motions and
/// the pinned rings' translations.
pub(super) fn free_columns(basis: &Basis, drive: &str, pins: &[PinnedRing]) -> Vec<usize> {
    basis
        .columns
        .iter()
        .enumerate()
        .filter(|(_, c)| {
            !matches!(&c.kind, ColumnKind::RigidInterface { interface, dof }
                if interface == drive
                    || (*dof < 3 && pins.iter().any(|p| p.name == *interface)))
        })
        .map(|(j, _)| j)
        .collect()
}
