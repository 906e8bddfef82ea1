//! The App. B slab (and the same mesh standing as the §5.3.3 plank) from trilinear bricks.

use crate::error::MeshError;
use std::collections::BTreeSet;

use faer::Mat;

use super::{DofMap, FeModel, HEX8_EDGES, RigidMotions, hex8_consistent_mass, hex8_stiffness};
use crate::{
    Result,
    linalg::{MassMatrix, SparseAssembly, SparsityPattern},
};

/// Meshes of up to this many bricks draw every brick edge.
const SMALL_MESH_BRICKS: usize = 64;
/// Grid lines drawn per face and direction on a refined mesh.
const DRAWN_LINES: usize = 8;

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
    /// Consistent mass ($\rho\int N^TN\,dV$ per brick, sparse) instead of the thesis' lumped
    /// one. Only with it are the free-free frequencies Rayleigh–Ritz upper bounds that fall
    /// under nested refinement; lumping lowers them.
    pub consistent_mass: bool,
}

/// The App. B slab as stored in `assets/thesis/slab-app-b.toml`.
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct SlabAsset {
    size: [f64; 3],
    bricks: [usize; 3],
    youngs_modulus: f64,
    poisson_ratio: f64,
    total_mass: f64,
}

impl Default for SlabParameters {
    /// The App. B values, read from the embedded `assets/thesis/slab-app-b.toml`; lumped mass.
    fn default() -> Self {
        let a: SlabAsset = crate::assets::parameters("thesis/slab-app-b.toml");
        Self {
            size: a.size,
            bricks: a.bricks,
            youngs_modulus: a.youngs_modulus,
            poisson_ratio: a.poisson_ratio,
            total_mass: a.total_mass,
            consistent_mass: false,
        }
    }
}

impl SlabParameters {
    /// The App. B slab (same 4 × 2 × 1 m body, material and total mass) meshed with
    /// `bricks` = [NX, NY, NZ] bricks; `[4, 2, 1]` is App. B itself. A zero count is
    /// [`MeshError::NoBricks`].
    pub fn refined(bricks: [usize; 3]) -> Result<Self> {
        if let Some(d) = (0..3).find(|&d| bricks[d] == 0) {
            return Err(MeshError::NoBricks {
                axis: ["x", "y", "z"][d],
            }
            .into());
        }
        Ok(Self {
            bricks,
            ..Default::default()
        })
    }

    /// Number of nodes of the mesh.
    pub fn node_count(&self) -> usize {
        self.bricks.iter().map(|&b| b.max(1) + 1).product()
    }

    /// Number of DOF (three per node).
    pub fn dof_count(&self) -> usize {
        3 * self.node_count()
    }

    /// The 1-based number of the node nearest to `position` (m, slab lying flat), in the
    /// numbering of [`slab`]: top layer first, ξ-major, η-minor (Table B-1 for App. B).
    pub fn nearest_node(&self, position: [f64; 3]) -> usize {
        let [nx, ny, nz] = self.bricks.map(|b| b.max(1));
        let index = |d: usize, n: usize| {
            ((position[d] / self.size[d] * n as f64).round().max(0.0) as usize).min(n)
        };
        let (ix, iy) = (index(0, nx), index(1, ny));
        let iz_from_top = nz - index(2, nz);
        iz_from_top * (nx + 1) * (ny + 1) + ix * (ny + 1) + iy + 1
    }

    /// The four bottom corners, 1-based (App. B: nodes 16, 18, 28, 30).
    pub fn bottom_corners(&self) -> [usize; 4] {
        let [lx, ly, _] = self.size;
        [[0.0, 0.0], [0.0, ly], [lx, 0.0], [lx, ly]].map(|[x, y]| self.nearest_node([x, y, 0.0]))
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

/// The bricks of the mesh as 0-based node lists in the local order of
/// [`LOCAL_NODES`](super::HEX8_LOCAL_NODES) (lower ζ face counter-clockwise, then the upper),
/// ξ-major, then η, then ζ from the top; for App. B the eight bricks of
/// `assets/thesis/slab-bricks-app-b.txt`.
pub fn slab_bricks(p: &SlabParameters) -> Vec<[usize; 8]> {
    let [nx, ny, nz] = p.bricks.map(|b| b.max(1));
    let py = ny + 1;
    let layer = (nx + 1) * py;
    let index = |ix: usize, iy: usize, iz_from_top: usize| iz_from_top * layer + ix * py + iy;
    let mut elements = Vec::with_capacity(nx * ny * nz);
    for ix in 0..nx {
        for iy in 0..ny {
            for izb in 0..nz {
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
    elements
}

/// The mesh's nodes, layer by layer from the top (ζ = size_z), each `place`d.
fn brick_nodes(p: &SlabParameters, place: &impl Fn([f64; 3]) -> [f64; 3]) -> Vec<[f64; 3]> {
    let [nx, ny, nz] = p.bricks.map(|b| b.max(1));
    let (px, py) = (nx + 1, ny + 1);
    let layer = px * py;
    let h = [
        p.size[0] / nx as f64,
        p.size[1] / ny as f64,
        p.size[2] / nz as f64,
    ];
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
    nodes
}

/// Which brick edges are drawn: a small mesh shows every one; a refined one only grid lines on
/// the surface, at most [`DRAWN_LINES`] per face and direction (full resolution along each
/// line), so an animated mode of a 150 000-DOF mesh stays a few thousand points per frame.
struct EdgeDrawing {
    /// Nodes per layer and per row of a layer.
    layer: usize,
    py: usize,
    refined: bool,
    n_per: [usize; 3],
    stride: [usize; 3],
}

impl EdgeDrawing {
    fn of(p: &SlabParameters) -> Self {
        let [nx, ny, nz] = p.bricks.map(|b| b.max(1));
        let py = ny + 1;
        let refined = nx * ny * nz > SMALL_MESH_BRICKS;
        let n_per = [nx, ny, nz];
        let stride = n_per.map(|n| {
            if refined {
                n.div_ceil(DRAWN_LINES).max(1)
            } else {
                1
            }
        });
        Self {
            layer: (nx + 1) * py,
            py,
            refined,
            n_per,
            stride,
        }
    }

    /// The grid position (x, y, layer from the top) of node `c`.
    fn grid(&self, c: usize) -> [usize; 3] {
        let iz = c / self.layer;
        let rest = c % self.layer;
        [rest / self.py, rest % self.py, iz]
    }

    fn on_grid(&self, g: [usize; 3], d: usize) -> bool {
        g[d].is_multiple_of(self.stride[d]) || g[d] == self.n_per[d]
    }

    fn on_face(&self, g: [usize; 3], d: usize) -> bool {
        g[d] == 0 || g[d] == self.n_per[d]
    }

    /// Whether node `c` is drawn: every node of a small mesh, a surface node of a refined one.
    fn drawn(&self, c: usize) -> bool {
        let g = self.grid(c);
        !self.refined || (0..3).any(|d| self.on_face(g, d))
    }

    /// Whether the edge `u`–`v` (along one direction) lies on a face and on a drawn grid line.
    fn on_one_line(&self, u: usize, v: usize) -> bool {
        if !self.refined {
            return true;
        }
        let (gu, gv) = (self.grid(u), self.grid(v));
        let Some(a) = (0..3).find(|&d| gu[d] != gv[d]) else {
            return false;
        };
        let others: Vec<usize> = (0..3).filter(|&d| d != a).collect();
        let (p, q) = (others[0], others[1]);
        (self.on_face(gu, p) && self.on_grid(gu, q)) || (self.on_face(gu, q) && self.on_grid(gu, p))
    }
}

fn brick_mesh(name: &str, p: &SlabParameters, place: impl Fn([f64; 3]) -> [f64; 3]) -> FeModel {
    let [nx, ny, nz] = p.bricks.map(|b| b.max(1));
    let nodes = brick_nodes(p, &place);
    // Connectivity first (the sparsity pattern), values second.
    let elements = slab_bricks(p);
    let pattern =
        SparsityPattern::from_elements(nodes.len(), 3, elements.iter().map(|c| c.as_slice()));
    let mut mass_assembly = p
        .consistent_mass
        .then(|| SparseAssembly::new(pattern.clone()));
    let mut assembly = SparseAssembly::new(pattern);
    let mut mass = vec![0.0; 3 * nodes.len()];
    let brick_mass = p.total_mass / (nx * ny * nz) as f64;
    let mut edges = BTreeSet::new();
    let drawing = EdgeDrawing::of(p);
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
        if let Some(ma) = mass_assembly.as_mut() {
            let density = brick_mass / brick_volume(&x);
            ma.add_element(&dofs, hex8_consistent_mass(&x, density).as_ref());
        }
        for &c in conn {
            for d in 0..3 {
                mass[3 * c + d] += brick_mass / 8.0;
            }
        }
        for (a, b) in HEX8_EDGES {
            let (u, v) = (conn[a].min(conn[b]), conn[a].max(conn[b]));
            if drawing.drawn(u) && drawing.drawn(v) && drawing.on_one_line(u, v) {
                edges.insert([u, v]);
            }
        }
    }
    let k = assembly.finish();
    let m = match mass_assembly {
        Some(ma) => MassMatrix::Consistent(ma.finish()),
        None => MassMatrix::Lumped(mass),
    };
    FeModel {
        name: name.into(),
        dofs: DofMap::solid(),
        nodes,
        edges: edges.into_iter().collect(),
        k,
        m,
        rigid_motions: RigidMotions::FromGeometry,
    }
}

/// Volume (m³) of a brick whose nodes are in the local order of
/// [`LOCAL_NODES`](super::HEX8_LOCAL_NODES) (2×2×2 Gauss, exact for trilinear bricks).
fn brick_volume(x: &[[f64; 3]; 8]) -> f64 {
    let unit = hex8_consistent_mass(x, 1.0);
    // Σ_ab M_ab over one direction = ρ V.
    (0..8)
        .flat_map(|a| (0..8).map(move |b| (a, b)))
        .map(|(a, b)| unit[(3 * a, 3 * b)])
        .sum()
}
