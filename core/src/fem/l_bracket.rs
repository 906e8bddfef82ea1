//! An L-shaped steel bracket of trilinear bricks with a bolt hole: a body that does not come
//! from the thesis, generated here and stored in `assets/bodies/l-bracket/` as the example of
//! the body-file format.
//!
//! The base flange lies in the x-y plane, the upright flange stands at x = 0 and rises along
//! z; a square hole (the brick-mesh stand-in for a bolt hole) goes through the base. The bolt
//! clamps the hole's walls, so the node set `bolt_hole` (every node on the walls) is the
//! interface a reduction keeps; `tip` (the upright's top edge) is where a load or sensor goes.

use std::collections::{BTreeMap, BTreeSet};

use super::{DofMap, FeModel, HEX8_EDGES, RigidMotions, hex8_consistent_mass, hex8_stiffness};
use crate::linalg::{MassMatrix, SparseAssembly, SparsityPattern};

/// Parameters of the bracket. Defaults: a 60 × 30 mm steel base 10 mm thick, an upright
/// 10 mm thick rising 40 mm above it (50 mm overall), a 10 × 10 mm hole centred 40 mm from the upright, on
/// 5 mm bricks (438 nodes, 1 314 DOF).
#[derive(Debug, Clone, PartialEq)]
pub struct LBracketParameters {
    /// Brick edge, m.
    pub brick: f64,
    /// Bricks of the base along x, y, z (length, width, thickness).
    pub base: [usize; 3],
    /// Bricks of the upright above the base along z (its thickness along x is the base's).
    pub upright_height: usize,
    /// The hole: first brick along x and y and its size in bricks (through the thickness).
    pub hole: [usize; 4],
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Density, kg/m³.
    pub density: f64,
}

impl Default for LBracketParameters {
    fn default() -> Self {
        Self {
            brick: 0.005,
            base: [12, 6, 2],
            upright_height: 8,
            hole: [7, 2, 2, 2],
            youngs_modulus: 210e9,
            poisson_ratio: 0.3,
            density: 7850.0,
        }
    }
}

/// The bracket (consistent mass) and its node sets (1-based): `bolt_hole`, `tip`, `base_end`.
pub fn l_bracket(p: &LBracketParameters) -> (FeModel, BTreeMap<String, Vec<usize>>) {
    let [bx, by, bz] = p.base;
    let t = bz; // upright thickness in bricks along x
    let [hx, hy, hw, hd] = p.hole;
    let in_hole = |i: usize, j: usize| i >= hx && i < hx + hw && j >= hy && j < hy + hd;
    let mut cells = Vec::new();
    for i in 0..bx {
        for j in 0..by {
            for k in 0..bz {
                if !in_hole(i, j) {
                    cells.push([i, j, k]);
                }
            }
        }
    }
    for i in 0..t {
        for j in 0..by {
            for k in bz..bz + p.upright_height {
                cells.push([i, j, k]);
            }
        }
    }
    // Nodes: every grid corner of a cell, numbered x-major, then y, then z.
    let mut corners = BTreeSet::new();
    for c in &cells {
        for d in 0..8 {
            corners.insert(corner(*c, d));
        }
    }
    let index: BTreeMap<[usize; 3], usize> =
        corners.iter().enumerate().map(|(n, &g)| (g, n)).collect();
    let nodes: Vec<[f64; 3]> = corners
        .iter()
        .map(|g| g.map(|x| x as f64 * p.brick))
        .collect();
    let elements: Vec<[usize; 8]> = cells
        .iter()
        .map(|&c| std::array::from_fn(|d| index[&corner(c, d)]))
        .collect();
    let pattern =
        SparsityPattern::from_elements(nodes.len(), 3, elements.iter().map(|e| e.as_slice()));
    let mut k = SparseAssembly::new(pattern.clone());
    let mut m = SparseAssembly::new(pattern);
    let x0 = elements[0].map(|n| nodes[n]);
    let ke = hex8_stiffness(&x0, p.youngs_modulus, p.poisson_ratio);
    let me = hex8_consistent_mass(&x0, p.density);
    let mut edges = BTreeSet::new();
    for e in &elements {
        let dofs: Vec<usize> = e
            .iter()
            .flat_map(|&n| [3 * n, 3 * n + 1, 3 * n + 2])
            .collect();
        k.add_element(&dofs, ke.as_ref());
        m.add_element(&dofs, me.as_ref());
        for (a, b) in HEX8_EDGES {
            edges.insert([e[a].min(e[b]), e[a].max(e[b])]);
        }
    }
    // Only the surface edges are drawn: an edge shared by four cells is inside.
    let mut count: BTreeMap<[usize; 2], usize> = BTreeMap::new();
    for e in &elements {
        for (a, b) in HEX8_EDGES {
            *count.entry([e[a].min(e[b]), e[a].max(e[b])]).or_default() += 1;
        }
    }
    let edges: Vec<[usize; 2]> = edges.into_iter().filter(|e| count[e] < 4).collect();

    let mut sets = BTreeMap::new();
    let select = |f: &dyn Fn([usize; 3]) -> bool| -> Vec<usize> {
        corners
            .iter()
            .filter(|&&g| f(g))
            .map(|g| index[g] + 1)
            .collect()
    };
    sets.insert(
        "bolt_hole".to_string(),
        select(&|[i, j, k]| {
            k <= bz
                && i >= hx
                && i <= hx + hw
                && j >= hy
                && j <= hy + hd
                && (i == hx || i == hx + hw || j == hy || j == hy + hd)
        }),
    );
    let top = bz + p.upright_height;
    sets.insert("tip".to_string(), select(&|[_, _, k]| k == top));
    sets.insert("base_end".to_string(), select(&|[i, _, _]| i == bx));
    let model = FeModel {
        name: "l_bracket".into(),
        dofs: DofMap::solid(),
        nodes,
        edges,
        k: k.finish(),
        m: MassMatrix::Consistent(m.finish()),
        rigid_motions: RigidMotions::FromGeometry,
    };
    (model, sets)
}

/// Grid corner `d` of cell `c` in the local order of
/// [`LOCAL_NODES`](super::HEX8_LOCAL_NODES): the lower face counter-clockwise, then the
/// upper one.
fn corner(c: [usize; 3], d: usize) -> [usize; 3] {
    let [i, j, k] = c;
    let (di, dj) = [(0, 0), (1, 0), (1, 1), (0, 1)][d % 4];
    [i + di, j + dj, k + d / 4]
}
