//! The App. B slab (and the same mesh standing as the §5.3.3 plank) from trilinear bricks.

use std::collections::BTreeSet;

use faer::Mat;

use super::{FeModel, hex8_stiffness};
use crate::linalg::{MassMatrix, SparseAssembly, SparsityPattern};

/// Parameters of the App. B slab. Defaults are the thesis values.
#[derive(Debug, Clone, PartialEq)]
pub struct SlabParameters {
    /// Extents along ξ, η, ζ in m.
    pub size: [f64; 3],
    /// Bricks along ξ, η, ζ (App. B: 4 × 2 × 1 unit cubes).
    pub bricks: [usize; 3],
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio.
    pub poisson_ratio: f64,
    /// Total mass, kg, lumped equally to each brick's eight nodes (Table B-1: 62.4 kg).
    pub total_mass: f64,
}

impl Default for SlabParameters {
    fn default() -> Self {
        Self {
            size: [4.0, 2.0, 1.0],
            bricks: [4, 2, 1],
            youngs_modulus: 0.2e6,
            poisson_ratio: 0.33,
            total_mass: 62.4,
        }
    }
}

/// The slab lying flat, numbered as Table B-1: the top layer (ζ = 1) first, ξ-major and
/// η-minor inside a layer (node 1 at (0,0,1), node 16 at the origin, node 30 at (4,2,0)).
pub fn slab(p: &SlabParameters) -> FeModel {
    brick_mesh("slab", p, |q| q)
}

/// The same mesh standing upright (§5.3.3): the slab's top face becomes the plank's front face
/// (y = 0, nodes 1–15), its η becomes the height z and its ζ the depth, so node 22 is behind
/// node 7 and nodes 3 and 15 are the top corners of the front face.
pub fn plank(p: &SlabParameters) -> FeModel {
    let depth = p.size[2];
    brick_mesh("plank", p, move |q| [q[0], depth - q[2], q[1]])
}

fn brick_mesh(name: &str, p: &SlabParameters, place: impl Fn([f64; 3]) -> [f64; 3]) -> FeModel {
    let [nx, ny, nz] = p.bricks.map(|b| b.max(1));
    let (px, py) = (nx + 1, ny + 1);
    let layer = px * py;
    let h = [
        p.size[0] / nx as f64,
        p.size[1] / ny as f64,
        p.size[2] / nz as f64,
    ];
    // Layer 0 is the top (ζ = size_z).
    let index = |ix: usize, iy: usize, iz_from_top: usize| iz_from_top * layer + ix * py + iy;
    let mut nodes = vec![[0.0; 3]; layer * (nz + 1)];
    for iz in 0..=nz {
        for ix in 0..=nx {
            for iy in 0..=ny {
                let q = [
                    ix as f64 * h[0],
                    iy as f64 * h[1],
                    p.size[2] - iz as f64 * h[2],
                ];
                nodes[index(ix, iy, iz)] = place(q);
            }
        }
    }
    // Connectivity first (the sparsity pattern), values second.
    let mut elements = Vec::with_capacity(nx * ny * nz);
    for ix in 0..nx {
        for iy in 0..ny {
            for izb in 0..nz {
                // Local order of hex8::LOCAL_NODES: bottom face (lower ζ) then top.
                let (bot, top) = (izb + 1, izb);
                elements.push([
                    index(ix, iy, bot),
                    index(ix + 1, iy, bot),
                    index(ix + 1, iy + 1, bot),
                    index(ix, iy + 1, bot),
                    index(ix, iy, top),
                    index(ix + 1, iy, top),
                    index(ix + 1, iy + 1, top),
                    index(ix, iy + 1, top),
                ]);
            }
        }
    }
    let pattern =
        SparsityPattern::from_elements(nodes.len(), 3, elements.iter().map(|c| c.as_slice()));
    let mut assembly = SparseAssembly::new(pattern);
    let mut mass = vec![0.0; 3 * nodes.len()];
    let brick_mass = p.total_mass / (nx * ny * nz) as f64;
    let mut edges = BTreeSet::new();
    // Bricks of one mesh are congruent translates: the element matrix is computed once per
    // shape (node offsets from the first local node), not once per brick.
    let mut cached: Option<([[f64; 3]; 8], Mat<f64>)> = None;
    for conn in &elements {
        let x = conn.map(|c| nodes[c]);
        let shape = x.map(|q| [q[0] - x[0][0], q[1] - x[0][1], q[2] - x[0][2]]);
        let same = cached.as_ref().is_some_and(|(s, _)| {
            s.iter()
                .flatten()
                .zip(shape.iter().flatten())
                .all(|(a, b)| (a - b).abs() <= 1e-12 * (1.0 + a.abs()))
        });
        if !same {
            cached = Some((shape, hex8_stiffness(&x, p.youngs_modulus, p.poisson_ratio)));
        }
        let ke = &cached.as_ref().expect("element matrix computed above").1;
        let dofs: Vec<usize> = conn
            .iter()
            .flat_map(|&c| [3 * c, 3 * c + 1, 3 * c + 2])
            .collect();
        assembly.add_element(&dofs, ke.as_ref());
        for &c in conn {
            for d in 0..3 {
                mass[3 * c + d] += brick_mass / 8.0;
            }
        }
        for (a, b) in [
            (0, 1),
            (1, 2),
            (2, 3),
            (3, 0),
            (4, 5),
            (5, 6),
            (6, 7),
            (7, 4),
            (0, 4),
            (1, 5),
            (2, 6),
            (3, 7),
        ] {
            let (u, v) = (conn[a].min(conn[b]), conn[a].max(conn[b]));
            edges.insert([u, v]);
        }
    }
    let k = assembly.finish();
    let m = MassMatrix::Lumped(mass);
    FeModel {
        name: name.into(),
        dim: 3,
        nodes,
        edges: edges.into_iter().collect(),
        k,
        m,
    }
}
