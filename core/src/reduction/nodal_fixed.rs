//! Nodal-fixed axes by column removal (§4.1, §5.4.1, Table 4-1).

use super::ReductionError;
use super::{Basis, ColumnKind};
use crate::{Error, Result, fem::Direction, fem::FeModel, linalg::select_cols};

/// One row of Table 4-1: the axis through node j and the second axis of the plane node k lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TableConfiguration {
    /// The axis that goes through node j.
    pub axis: Direction,
    /// With `axis`, spans the plane node k stays on.
    pub plane_with: Direction,
}

impl TableConfiguration {
    /// The six configurations of Table 4-1, in table order.
    pub const ALL: [TableConfiguration; 6] = [
        TableConfiguration::new(Direction::X, Direction::Y),
        TableConfiguration::new(Direction::X, Direction::Z),
        TableConfiguration::new(Direction::Y, Direction::Z),
        TableConfiguration::new(Direction::Y, Direction::X),
        TableConfiguration::new(Direction::Z, Direction::X),
        TableConfiguration::new(Direction::Z, Direction::Y),
    ];

    /// A configuration; see [`NodalFixedAxes::anchored_dofs`] for its validation.
    pub const fn new(axis: Direction, plane_with: Direction) -> Self {
        Self { axis, plane_with }
    }
}

/// A nodal-fixed frame: origin at node i, an axis through node j, node k on a coordinate
/// plane. Six deflections (three in 2-D) are zero; removing their columns from Ψ enforces it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodalFixedAxes {
    /// Node i at the origin (1-based).
    pub origin: usize,
    /// Node j on the axis.
    pub axis_node: usize,
    /// Node k on the plane (ignored for planar bodies).
    pub plane_node: usize,
    /// Which Table 4-1 row.
    pub configuration: TableConfiguration,
}

impl NodalFixedAxes {
    /// The §7.2 slab frame: origin node 16, ξ through node 28, node 18 on the ξη plane.
    pub fn slab_default() -> Self {
        Self {
            origin: 16,
            axis_node: 28,
            plane_node: 18,
            configuration: TableConfiguration::ALL[0],
        }
    }

    /// The anchored coordinates (set o of Eq. 4.1) as DOF indices, origin first.
    pub fn anchored_dofs(&self, model: &FeModel) -> Result<Vec<(usize, Direction, usize)>> {
        let TableConfiguration { axis, plane_with } = self.configuration;
        if axis == plane_with {
            return Err(ReductionError::AxesPlaneRepeated { axis: axis.name() }.into());
        }
        let nodes: &[usize] = if model.spatial_dim() == 3 {
            &[self.origin, self.axis_node, self.plane_node]
        } else {
            &[self.origin, self.axis_node]
        };
        for (a, &n) in nodes.iter().enumerate() {
            model.node_index(n)?;
            if nodes[..a].contains(&n) {
                return Err(ReductionError::AxesNodeRepeated { node: n }.into());
            }
        }
        let dims: Vec<Direction> = Direction::ALL[..model.spatial_dim()].to_vec();
        if !dims.contains(&axis) || (model.spatial_dim() == 3 && !dims.contains(&plane_with)) {
            return Err(ReductionError::AxesOutOfPlane {
                body: (&model.name).into(),
            }
            .into());
        }
        let mut out = Vec::new();
        for &d in &dims {
            out.push((self.origin, d, model.dof(self.origin, d)?));
        }
        for &d in dims.iter().filter(|&&d| d != axis) {
            out.push((self.axis_node, d, model.dof(self.axis_node, d)?));
        }
        if model.spatial_dim() == 3 {
            let normal = *dims
                .iter()
                .find(|&&d| d != axis && d != plane_with)
                .expect("three directions, two excluded");
            out.push((self.plane_node, normal, model.dof(self.plane_node, normal)?));
        }
        Ok(out)
    }

    /// Removes the anchored coordinates' columns from Ψ (Table 7-2's third column). Each
    /// anchored DOF must be a boundary column (unit there, zero at the other boundary DOF),
    /// so that the anchored rows of what remains are zero.
    pub fn apply(&self, model: &FeModel, basis: &Basis) -> Result<Basis> {
        let anchored = self.anchored_dofs(model)?;
        let mut remove = Vec::new();
        for &(node, dir, dof) in &anchored {
            let col = basis
                .columns
                .iter()
                .position(|c| c.dof == Some(dof) && !matches!(c.kind, ColumnKind::Normal { .. }));
            match col {
                Some(j) => remove.push(j),
                None => {
                    return Err(Error::Reduction(ReductionError::AnchorNotInBasis {
                        node,
                        direction: dir.name(),
                        method: basis.method.name(),
                    }));
                }
            }
        }
        let keep: Vec<usize> = (0..basis.size()).filter(|j| !remove.contains(j)).collect();
        let psi = select_cols(basis.psi.as_ref(), &keep);
        // The anchored rows must now vanish (footnote to Table 7-2).
        let scale = crate::linalg::max_abs(psi.as_ref()).max(1.0);
        for &(node, dir, dof) in &anchored {
            let row_max = (0..psi.ncols()).fold(0.0f64, |m, j| m.max(psi[(dof, j)].abs()));
            if row_max > 1e-9 * scale {
                return Err(Error::Reduction(ReductionError::AnchorNotInBasis {
                    node,
                    direction: dir.name(),
                    method: basis.method.name(),
                }));
            }
        }
        Ok(Basis {
            method: basis.method,
            psi,
            columns: keep.iter().map(|&j| basis.columns[j].clone()).collect(),
            statistics: basis.statistics,
        })
    }
}
