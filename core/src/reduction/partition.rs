//! The boundary/interior split of Eq. (6.1), the rigid motions of a free body's interior,
//! the checks of DOF sets, and the column descriptions every CMS method's basis carries (the
//! interior problem itself, its modes and constraint modes: `interior_problem.rs`).

use super::ReductionError;
use crate::error::{DofSetName, DofSetProblem, FreeMotion};

use faer::{Mat, MatRef};

use crate::{
    Error, Result,
    fem::{FeModel, NodeIndex},
};

/// DOF sets b (boundary) and i (interior) of Eq. (6.1), and the DOF held at zero (a clamp)
/// that belong to neither: a basis has zero rows there.
#[derive(Debug, Clone, PartialEq)]
pub struct Partition {
    /// Boundary nodes, 1-based, in the order given (for a DOF-wise boundary: the nodes its
    /// DOF belong to).
    pub boundary_nodes: Vec<usize>,
    /// Boundary DOF indices (set b), node by node.
    pub b: Vec<usize>,
    /// Interior DOF indices (set i), ascending.
    pub i: Vec<usize>,
    /// DOF held at zero (ascending): neither boundary nor interior.
    pub held: Vec<usize>,
}

impl Partition {
    /// Splits `model`'s DOF by the 1-based `boundary_nodes`.
    pub fn new(model: &FeModel, boundary_nodes: &[usize]) -> Result<Self> {
        if boundary_nodes.is_empty() {
            return Err(Error::Reduction(ReductionError::NoBoundary));
        }
        let b = model.dofs_of_nodes(boundary_nodes)?;
        let mut is_boundary = vec![false; model.dof_count()];
        for &d in &b {
            is_boundary[d] = true;
        }
        let i: Vec<usize> = (0..model.dof_count())
            .filter(|&d| !is_boundary[d])
            .collect();
        if i.is_empty() {
            return Err(Error::Reduction(ReductionError::NoInterior {
                nodes: boundary_nodes.to_vec(),
            }));
        }
        Ok(Self {
            boundary_nodes: boundary_nodes.to_vec(),
            b,
            i,
            held: Vec::new(),
        })
    }

    /// Splits `model`'s DOF into the boundary DOF `b` (in the order given, e.g. Witteveen's
    /// seven input/output DOF), the DOF `held` at zero (a clamp) and the interior: the rest.
    /// A DOF out of range or listed twice is `ReductionError::InvalidDofSet`.
    pub fn from_dofs(model: &FeModel, b: &[usize], held: &[usize]) -> Result<Self> {
        let n = model.dof_count();
        let mut role = vec![0u8; n];
        check_dof_set(model, "boundary", b, &mut role, 1)?;
        if !held.is_empty() {
            check_dof_set(model, "held", held, &mut role, 2)?;
        }
        let i: Vec<usize> = (0..n).filter(|&d| role[d] == 0).collect();
        if i.is_empty() {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: "boundary".into(),
                problem: DofSetProblem::NothingLeft,
            }));
        }
        let mut boundary_nodes: Vec<usize> = Vec::new();
        for &d in b {
            let node = model.dof_node(d).0.number();
            if !boundary_nodes.contains(&node) {
                boundary_nodes.push(node);
            }
        }
        let mut held = held.to_vec();
        held.sort_unstable();
        Ok(Self {
            boundary_nodes,
            b: b.to_vec(),
            i,
            held,
        })
    }

    /// Places a boundary block (rows of b) and an interior block (rows of i) into a Ψ with
    /// the body's DOF order.
    pub fn assemble(&self, top: MatRef<'_, f64>, bottom: MatRef<'_, f64>) -> Mat<f64> {
        assert_eq!(top.ncols(), bottom.ncols());
        assert_eq!((top.nrows(), bottom.nrows()), (self.b.len(), self.i.len()));
        let n = self.b.len() + self.i.len() + self.held.len();
        let mut psi = Mat::zeros(n, top.ncols());
        for c in 0..top.ncols() {
            for (r, &dof) in self.b.iter().enumerate() {
                psi[(dof, c)] = top[(r, c)];
            }
            for (r, &dof) in self.i.iter().enumerate() {
                psi[(dof, c)] = bottom[(r, c)];
            }
        }
        psi
    }

    /// The unit boundary block $I$ of Ψ followed by `extra` zero columns.
    pub fn unit_top(&self, extra: usize) -> Mat<f64> {
        let nb = self.b.len();
        Mat::from_fn(nb, nb + extra, |r, c| if r == c { 1.0 } else { 0.0 })
    }
}

/// The rigid-body motions the boundary DOF leave free (none when the rigid motions restricted
/// to the boundary DOF have full rank), each described as a rotation about an axis or a
/// translation.
pub(super) fn free_rigid_motions(model: &FeModel, p: &Partition) -> Result<Vec<FreeMotion>> {
    let rigid = model.dofs.rigid_body_count();
    // Rigid motions about the body's centroid, rotations scaled by its size so the columns
    // are commensurate: u = t + (w / L) × (x − c).
    let count = model.node_count() as f64;
    let mut c = [0.0; 3];
    for x in &model.nodes {
        for d in 0..3 {
            c[d] += x[d] / count;
        }
    }
    let size = model.size().max(f64::MIN_POSITIVE);
    // Held DOF restrain as boundary DOF do.
    let restrained: Vec<usize> = p.b.iter().chain(&p.held).copied().collect();
    let r_b = Mat::from_fn(restrained.len(), rigid, |row, col| {
        let (node, dof) = model.dof_node(restrained[row]);
        let x = model.position(node);
        let r = [
            (x[0] - c[0]) / size,
            (x[1] - c[1]) / size,
            (x[2] - c[2]) / size,
        ];
        // A rotation DOF takes the scaled rotation's component times the size: a row
        // scaling, which leaves the null space as it is.
        let (t, w) = model.dofs.rigid_motion(col);
        dof.rigid_motion(r, t, w)
    });
    // Null space of R_b from the eigenvectors of R_bᵀR_b (6 × 6).
    let gram = r_b.transpose() * &r_b;
    let evd = crate::linalg::symmetric_eigen(gram.as_ref(), "boundary rigid-motion rank")?;
    let largest = evd.values[rigid - 1].max(f64::MIN_POSITIVE);
    let free: Vec<usize> = (0..rigid)
        .filter(|&k| evd.values[k] <= 1e-12 * largest)
        .collect();
    Ok(free
        .iter()
        .map(|&k| describe_motion(model, p, (c, size), evd.vectors.col(k)))
        .collect())
}

/// A free rigid motion `v` (translation and rotation about the centroid `c`, the rotation
/// scaled by the body's `size`) as a translation or a rotation about an axis, the axis named
/// by a boundary node of `p` it passes through where there is one.
fn describe_motion(
    model: &FeModel,
    p: &Partition,
    (c, size): ([f64; 3], f64),
    v: faer::ColRef<'_, f64>,
) -> FreeMotion {
    if model.spatial_dim() == 2 {
        let w = v[2] / size;
        let t = [v[0] - (-w * c[1]), v[1] - (w * c[0])];
        if w.abs() * size < 1e-9 {
            return FreeMotion::Translation {
                along: [v[0], v[1], 0.0],
                planar: true,
            };
        }
        // Rotation about the point a with t = ω ẑ × (−a).
        return FreeMotion::PlanarRotation {
            about: [-t[1] / w, t[0] / w],
        };
    }
    let w = [v[3] / size, v[4] / size, v[5] / size];
    let wn = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    if wn * size < 1e-9 {
        return FreeMotion::Translation {
            along: [v[0], v[1], v[2]],
            planar: false,
        };
    }
    // Motion t + ω × (x − c): the axis passes through a = c + (ω × t)/|ω|².
    let t = [v[0], v[1], v[2]];
    let wxt = [
        w[1] * t[2] - w[2] * t[1],
        w[2] * t[0] - w[0] * t[2],
        w[0] * t[1] - w[1] * t[0],
    ];
    let a: Vec<f64> = (0..3).map(|d| c[d] + wxt[d] / (wn * wn)).collect();
    // Name a boundary node the axis passes through, if any (a point support).
    let unit = [w[0] / wn, w[1] / wn, w[2] / wn];
    // (Boundary node numbers were checked when the partition was made.)
    let through_node = p
        .boundary_nodes
        .iter()
        .filter_map(|&number| NodeIndex::of_number(number))
        .find(|&node| {
            let x = model.position(node);
            let d = [x[0] - a[0], x[1] - a[1], x[2] - a[2]];
            let along = d[0] * unit[0] + d[1] * unit[1] + d[2] * unit[2];
            let off = (0..3)
                .map(|k| (d[k] - along * unit[k]).powi(2))
                .sum::<f64>()
                .sqrt();
            off <= 1e-9 * size
        });
    let clean = |x: f64| if x.abs() < 1e-9 { 0.0 } else { x };
    let axis = unit.map(clean);
    match through_node {
        Some(node) => {
            let x = model.position(node);
            FreeMotion::Rotation {
                axis,
                point: [clean(x[0]), clean(x[1]), clean(x[2])],
                node: Some(node.number()),
            }
        }
        None => FreeMotion::Rotation {
            axis,
            point: [clean(a[0]), clean(a[1]), clean(a[2])],
            node: None,
        },
    }
}

/// Checks a DOF set against the body and against the sets already marked in `taken` (entry
/// per DOF: 0 free, otherwise the mark of the set that took it), then marks it with `mark`.
pub(crate) fn check_dof_set(
    model: &FeModel,
    set: impl Into<DofSetName>,
    dofs: &[usize],
    taken: &mut [u8],
    mark: u8,
) -> Result<()> {
    let set = set.into();
    let n = model.dof_count();
    if dofs.is_empty() {
        return Err(Error::Reduction(ReductionError::InvalidDofSet {
            set: set.clone(),
            problem: DofSetProblem::Empty,
        }));
    }
    for &d in dofs {
        if d >= n {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: set.clone(),
                problem: DofSetProblem::OutOfRange { dof: d, count: n },
            }));
        }
        if taken[d] == mark {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: set.clone(),
                problem: {
                    let (node, dof) = model.dof_node(d);
                    DofSetProblem::Twice {
                        node: node.number(),
                        dof: dof.name(),
                    }
                },
            }));
        }
        if taken[d] != 0 {
            return Err(Error::Reduction(ReductionError::InvalidDofSet {
                set: set.clone(),
                problem: {
                    let (node, dof) = model.dof_node(d);
                    DofSetProblem::InAnotherSet {
                        node: node.number(),
                        dof: dof.name(),
                    }
                },
            }));
        }
        taken[d] = mark;
    }
    Ok(())
}

/// Column descriptions of the boundary columns (one per boundary DOF).
pub(crate) fn boundary_columns(
    model: &FeModel,
    p: &Partition,
    kind: super::ColumnKind,
    prefix: &str,
) -> Vec<super::Column> {
    p.b.iter()
        .map(|&dof| super::Column {
            kind: kind.clone(),
            dof: Some(dof),
            label: format!("{prefix} {}", model.dof_label(dof)),
        })
        .collect()
}

/// Column descriptions of kept normal modes.
pub(crate) fn normal_columns(hz: &[f64]) -> Vec<super::Column> {
    hz.iter()
        .enumerate()
        .map(|(k, &hz)| super::Column {
            kind: super::ColumnKind::Normal { hz },
            dof: None,
            label: format!("normal {} ({hz:.4} Hz)", k + 1),
        })
        .collect()
}
