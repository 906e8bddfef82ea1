//! The boundary coordinates $q$ of a fixed-interface basis, $u_b = R\,q$: each boundary DOF
//! its own coordinate ($R = I$, the thesis' Eq. 6.1), or the nodes of a rigid (RBE2) interface
//! tied to the six DOF of its master ($R_S$ of [`super::RigidInterface`]).
//!
//! Every fixed-interface basis is linear in the boundary displacement, so a rigid interface's
//! columns are $[R_S;\,-K_{ii}^{-1}K_{ib}R_S]$: six right-hand sides per interface instead of
//! three per tied node. The fixed-interface modes are unchanged (the ring is held either way).

use crate::error::{DofSetName, DofSetProblem};
use faer::{Mat, sparse::SparseColMat};

use super::{Column, ColumnKind, MASTER_DOF_NAMES, ReductionError, RigidInterface};
use crate::{Result, fem::FeModel};

/// How one boundary DOF moves with the coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Tie {
    /// Its own coordinate (index into the coordinates).
    Own(usize),
    /// The rigid motion of the master whose six coordinates start at `first`: the DOF's
    /// motion under each unit master motion.
    Rigid { first: usize, row: [f64; 6] },
}

/// What one coordinate is.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Coordinate {
    /// A boundary DOF (index into the partition's b).
    Dof(usize),
    /// DOF `dof` (0–5: x, y, z, θx, θy, θz) of interface `interface`'s master.
    Master { interface: usize, dof: usize },
}

/// The map $u_b = R\,q$ from boundary coordinates to the boundary DOF b.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundaryCoordinates {
    /// One per boundary DOF, in b's order.
    ties: Vec<Tie>,
    /// One per coordinate: plain DOF in b's order, each interface's six where its first DOF
    /// stood.
    coordinates: Vec<Coordinate>,
    /// The rigid interfaces' names.
    interfaces: Vec<String>,
}

impl BoundaryCoordinates {
    /// Every one of the `nb` boundary DOF its own coordinate ($R = I$).
    pub fn plain(nb: usize) -> Self {
        Self {
            ties: (0..nb).map(Tie::Own).collect(),
            coordinates: (0..nb).map(Coordinate::Dof).collect(),
            interfaces: Vec::new(),
        }
    }

    /// The boundary DOF `b` with the nodes of each of `interfaces` tied to its master. Every
    /// DOF of a tied node must be in `b` and belong to one interface only
    /// ([`ReductionError::InvalidDofSet`] naming the DOF otherwise).
    pub fn tied(model: &FeModel, b: &[usize], interfaces: &[RigidInterface]) -> Result<Self> {
        let mut position = vec![usize::MAX; model.dof_count()];
        for (j, &dof) in b.iter().enumerate() {
            position[dof] = j;
        }
        // Per boundary DOF: tied into interface k with rigid-motion row, or not.
        let mut tied: Vec<Option<(usize, [f64; 6])>> = vec![None; b.len()];
        for (k, interface) in interfaces.iter().enumerate() {
            let set = || DofSetName::Interface {
                kind: "rbe2",
                name: (&interface.name).into(),
            };
            for (dof, row) in interface.rigid_motions(model)? {
                let j = position[dof];
                if j == usize::MAX {
                    return Err(ReductionError::InvalidDofSet {
                        set: set(),
                        problem: {
                            let (node, d) = model.dof_node(dof);
                            DofSetProblem::NotBoundary {
                                node: node.number(),
                                dof: d.name(),
                            }
                        },
                    }
                    .into());
                }
                if tied[j].is_some() {
                    return Err(ReductionError::InvalidDofSet {
                        set: set(),
                        problem: DofSetProblem::TiedTwice {
                            node: model.dof_node(dof).0.number(),
                        },
                    }
                    .into());
                }
                tied[j] = Some((k, row));
            }
        }
        let mut coordinates = Vec::new();
        let mut first = vec![usize::MAX; interfaces.len()];
        let mut ties = Vec::with_capacity(b.len());
        for (j, t) in tied.iter().enumerate() {
            match *t {
                None => {
                    ties.push(Tie::Own(coordinates.len()));
                    coordinates.push(Coordinate::Dof(j));
                }
                Some((k, row)) => {
                    if first[k] == usize::MAX {
                        first[k] = coordinates.len();
                        coordinates
                            .extend((0..6).map(|dof| Coordinate::Master { interface: k, dof }));
                    }
                    ties.push(Tie::Rigid {
                        first: first[k],
                        row,
                    });
                }
            }
        }
        Ok(Self {
            ties,
            coordinates,
            interfaces: interfaces.iter().map(|i| i.name.clone()).collect(),
        })
    }

    /// Number of coordinates.
    pub fn count(&self) -> usize {
        self.coordinates.len()
    }

    /// Whether a rigid interface ties any DOF.
    pub fn is_tied(&self) -> bool {
        !self.interfaces.is_empty()
    }

    /// $R$ (b × coordinates) followed by `extra` zero columns: the boundary rows of a basis.
    pub fn top(&self, extra: usize) -> Mat<f64> {
        let mut r = Mat::zeros(self.ties.len(), self.count() + extra);
        for (j, tie) in self.ties.iter().enumerate() {
            match *tie {
                Tie::Own(q) => r[(j, q)] = 1.0,
                Tie::Rigid { first, row } => {
                    for (q, w) in row.iter().enumerate() {
                        r[(j, first + q)] = *w;
                    }
                }
            }
        }
        r
    }

    /// $A\,R$, dense, for a sparse `a` whose columns are the boundary DOF (e.g. $K_{ib}$):
    /// each stored entry visited once per coordinate it moves with.
    pub fn times(&self, a: &SparseColMat<usize, f64>) -> Mat<f64> {
        assert_eq!(
            a.ncols(),
            self.ties.len(),
            "columns of A against boundary DOF"
        );
        let mut out = Mat::<f64>::zeros(a.nrows(), self.count());
        for (j, tie) in self.ties.iter().enumerate() {
            let rows = a.symbolic().row_idx_of_col_raw(j);
            let values = a.val_of_col(j);
            match *tie {
                Tie::Own(q) => {
                    for (&r, &v) in rows.iter().zip(values) {
                        out[(r, q)] += v;
                    }
                }
                Tie::Rigid { first, row } => {
                    for (q, &w) in row.iter().enumerate().filter(|(_, w)| **w != 0.0) {
                        for (&r, &v) in rows.iter().zip(values) {
                            out[(r, first + q)] += w * v;
                        }
                    }
                }
            }
        }
        out
    }

    /// Column descriptions of the coordinates: `kind` and `prefix` for plain boundary DOF of
    /// `b`, `rbe2 NAME x … θz` for a master's.
    pub fn columns(
        &self,
        model: &FeModel,
        b: &[usize],
        kind: ColumnKind,
        prefix: &str,
    ) -> Vec<Column> {
        self.coordinates
            .iter()
            .map(|c| match *c {
                Coordinate::Dof(j) => Column {
                    kind: kind.clone(),
                    dof: Some(b[j]),
                    label: format!("{prefix} {}", model.dof_label(b[j])),
                },
                Coordinate::Master { interface, dof } => Column {
                    kind: ColumnKind::RigidInterface {
                        interface: self.interfaces[interface].clone(),
                        dof,
                    },
                    dof: None,
                    label: format!(
                        "rbe2 {} {}",
                        self.interfaces[interface], MASTER_DOF_NAMES[dof]
                    ),
                },
            })
            .collect()
    }
}
