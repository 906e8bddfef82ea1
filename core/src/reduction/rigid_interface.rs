//! Rigid (RBE2) interfaces: a set of nodes tied to one 6-DOF master node, as FE codes define
//! them, so that a multibody code sees a bore or a flange as one joint of six DOF instead of
//! hundreds of boundary DOF.
//!
//! Every DOF of a tied node follows the master's rigid motion,
//! $u_s = u_m + \theta_m \times (x_s - x_m)$ (rotations of frame nodes: $\theta_s = \theta_m$),
//! i.e. $u_{b,S} = R_S\,q_m$ with $R_S$ the set's rigid-motion matrix. A basis whose boundary
//! columns are unit boundary displacements (constraint modes $[I; \Psi_s]$, modal truncation's
//! $[I; 0]$, mode condensation's $[I; \Psi_m]$) is linear in the boundary displacement, so
//! tying the set replaces its $3|S|$ columns $\Psi_S$ by the six $\Psi_S R_S$: the static
//! response to each rigid motion of the ring. That is exactly Craig–Bampton (or Guyan, modal
//! truncation) of the body transformed by hand with the master's six DOF as its boundary: the
//! interior is unchanged, $K'_{ib} = K_{ib}R$, so the constraint modes are
//! $-K_{ii}^{-1}K_{ib}R$, and the fixed-interface modes are those with the ring held.

use crate::error::{DofSetName, DofSetProblem};
use faer::Mat;

use super::{Basis, Column, ColumnKind};
use crate::{Result, error::ReductionError, fem::FeModel};

/// The names of a master node's six DOF, in column order.
pub const MASTER_DOF_NAMES: [&str; 6] = ["x", "y", "z", "θx", "θy", "θz"];

/// A node set tied rigidly to a master node.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidInterface {
    /// The interface's name (the node set's).
    pub name: String,
    /// The tied nodes, 1-based.
    pub nodes: Vec<usize>,
    /// The master point, in the body's length unit.
    pub master: [f64; 3],
}

impl RigidInterface {
    /// `nodes` tied to a master at their centroid (the mean of their positions).
    pub fn at_centroid(model: &FeModel, name: &str, nodes: &[usize]) -> Result<Self> {
        let mut centre = [0.0; 3];
        for &n in nodes {
            let x = model.position(model.node_index(n)?);
            for d in 0..3 {
                centre[d] += x[d] / nodes.len() as f64;
            }
        }
        if nodes.is_empty() {
            return Err(ReductionError::InvalidDofSet {
                set: DofSetName::Interface {
                    kind: "rbe2",
                    name: name.into(),
                },
                problem: DofSetProblem::NoNodes,
            }
            .into());
        }
        Ok(Self {
            name: name.into(),
            nodes: nodes.to_vec(),
            master: centre,
        })
    }

    /// $R_S$ row by row: for every DOF of the tied nodes (0-based, in node order), its motion
    /// under each of the master's six unit motions ($u_s = u_m + \theta_m \times r_s$).
    pub fn rigid_motions(&self, model: &FeModel) -> Result<Vec<(usize, [f64; 6])>> {
        rigid_motion_rows(model, &self.nodes, self.master)
    }
}

/// The rigid-motion matrix of `nodes` (1-based) about `master`, row by row: for every DOF of
/// the nodes (0-based, in node order), its motion under each of the master's six unit motions
/// ($u_s = u_m + \theta_m \times r_s$; rotations of frame nodes: $\theta_s = \theta_m$).
pub(crate) fn rigid_motion_rows(
    model: &FeModel,
    nodes: &[usize],
    master: [f64; 3],
) -> Result<Vec<(usize, [f64; 6])>> {
    let mut rows = Vec::with_capacity(3 * nodes.len());
    for &node in nodes {
        let x = model.position(model.node_index(node)?);
        let r = [x[0] - master[0], x[1] - master[1], x[2] - master[2]];
        for dof in model.dofs_of_nodes(&[node])? {
            let (_, d) = model.dof_node(dof);
            let mut row = [0.0; 6];
            for (q, value) in row.iter_mut().enumerate() {
                let mut t = [0.0; 3];
                let mut omega = [0.0; 3];
                if q < 3 {
                    t[q] = 1.0;
                } else {
                    omega[q - 3] = 1.0;
                }
                *value = d.rigid_motion(r, t, omega);
            }
            rows.push((dof, row));
        }
    }
    Ok(rows)
}

/// Tied column of Ψ: the interface it is tied into and its row of the rigid motions.
type Tied = Option<(usize, [f64; 6])>;

/// For every column of `basis`: kept as is (`None`), or tied into interface k with its
/// rigid-motion row. An interface DOF without a boundary column, or tied twice, is named.
fn tied_columns(
    model: &FeModel,
    basis: &Basis,
    interfaces: &[RigidInterface],
) -> Result<Vec<Tied>> {
    let boundary_column = |kind: &ColumnKind| {
        matches!(
            kind,
            ColumnKind::Constraint | ColumnKind::BoundaryMovement | ColumnKind::CondensedBoundary
        )
    };
    let mut tied: Vec<Tied> = vec![None; basis.size()];
    for (k, interface) in interfaces.iter().enumerate() {
        for (dof, row) in interface.rigid_motions(model)? {
            let j = basis
                .columns
                .iter()
                .position(|c| c.dof == Some(dof) && boundary_column(&c.kind))
                .ok_or_else(|| ReductionError::InvalidDofSet {
                    set: DofSetName::Interface {
                        kind: "rbe2",
                        name: (&interface.name).into(),
                    },
                    problem: {
                        let (node, d) = model.dof_node(dof);
                        DofSetProblem::NotInBoundary {
                            node: node.number(),
                            dof: d.name(),
                            method: basis.method.name(),
                        }
                    },
                })?;
            if tied[j].is_some() {
                return Err(ReductionError::InvalidDofSet {
                    set: DofSetName::Interface {
                        kind: "rbe2",
                        name: (&interface.name).into(),
                    },
                    problem: DofSetProblem::TiedTwice {
                        node: model.dof_node(dof).0.number(),
                    },
                }
                .into());
            }
            tied[j] = Some((k, row));
        }
    }
    Ok(tied)
}

/// Ties each interface's boundary columns of `basis` to its master's six DOF (see the module
/// docs): the columns of the interface's DOF (every DOF of its nodes must have one) are
/// replaced by six columns `rbe2 NAME x … θz` placed where the first of them stood; the other
/// columns are kept. A method without unit boundary columns (free-interface or Krylov bases,
/// Eitelberg) is a [`ReductionError::InvalidDofSet`] naming the DOF without a column.
pub fn tie_rigid_interfaces(
    model: &FeModel,
    basis: Basis,
    interfaces: &[RigidInterface],
) -> Result<Basis> {
    if interfaces.is_empty() {
        return Ok(basis);
    }
    // For every column of Ψ: kept as is, or tied into interface k with rigid-motion row r.
    let tied = tied_columns(model, &basis, interfaces)?;
    // The new columns: kept ones in order, each interface's six where its first column stood.
    enum Source {
        Kept(usize),
        Master(usize, usize),
    }
    let mut sources = Vec::new();
    let mut placed = vec![false; interfaces.len()];
    for (j, t) in tied.iter().enumerate() {
        match t {
            None => sources.push(Source::Kept(j)),
            Some((k, _)) if !placed[*k] => {
                placed[*k] = true;
                sources.extend((0..6).map(|q| Source::Master(*k, q)));
            }
            Some(_) => {}
        }
    }
    let n = basis.psi.nrows();
    let mut psi = Mat::<f64>::zeros(n, sources.len());
    let mut columns = Vec::with_capacity(sources.len());
    for (c, source) in sources.iter().enumerate() {
        match *source {
            Source::Kept(j) => {
                psi.col_mut(c).copy_from(basis.psi.col(j));
                columns.push(basis.columns[j].clone());
            }
            Source::Master(k, q) => {
                for (j, t) in tied.iter().enumerate() {
                    if let Some((kk, row)) = t
                        && *kk == k
                        && row[q] != 0.0
                    {
                        let w = row[q];
                        for i in 0..n {
                            psi[(i, c)] += w * basis.psi[(i, j)];
                        }
                    }
                }
                columns.push(Column {
                    kind: ColumnKind::RigidInterface {
                        interface: interfaces[k].name.clone(),
                        dof: q,
                    },
                    dof: None,
                    label: format!("rbe2 {} {}", interfaces[k].name, MASTER_DOF_NAMES[q]),
                });
            }
        }
    }
    Ok(Basis {
        method: basis.method,
        psi,
        columns,
        statistics: basis.statistics,
    })
}
