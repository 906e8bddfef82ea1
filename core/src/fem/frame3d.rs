//! Straight 3-D Euler–Bernoulli frame elements with six DOF per node (x, y, z, θx, θy, θz):
//! axial force, torsion and bending about both principal axes of the section, and a lumped
//! mass (translational mass and the section's rotary inertia about the axis, half of each
//! element at each end).

use crate::error::MeshError;
use faer::Mat;

use super::{DofMap, FeModel, NodeIndex, RigidMotions};
use crate::{
    Error, Result,
    linalg::{MassMatrix, SparseAssembly, SparsityPattern},
};

/// A homogeneous section and material of a frame.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameSection {
    /// Young's modulus, Pa (N/mm² in mm–t–s units).
    pub youngs_modulus: f64,
    /// Shear modulus, Pa (N/mm²).
    pub shear_modulus: f64,
    /// Density, kg/m³ (t/mm³).
    pub density: f64,
    /// Area, m².
    pub area: f64,
    /// Second moment about the section's local y axis (bending in the local x-z plane), m⁴.
    pub iy: f64,
    /// Second moment about the section's local z axis (bending in the local x-y plane), m⁴.
    pub iz: f64,
    /// Torsion constant, m⁴.
    pub torsion: f64,
}

impl FrameSection {
    /// A solid rectangle `width` (local y) × `height` (local z), m, with Saint-Venant's
    /// torsion constant $J \approx a b^3 (1/3 - 0.21 (b/a)(1 - b^4/(12a^4)))$, $a \ge b$.
    pub fn rectangle(
        width: f64,
        height: f64,
        youngs_modulus: f64,
        shear_modulus: f64,
        density: f64,
    ) -> Self {
        let (a, b) = if width >= height {
            (width, height)
        } else {
            (height, width)
        };
        let torsion =
            a * b.powi(3) * (1.0 / 3.0 - 0.21 * (b / a) * (1.0 - b.powi(4) / (12.0 * a.powi(4))));
        Self {
            youngs_modulus,
            shear_modulus,
            density,
            area: width * height,
            iy: width * height.powi(3) / 12.0,
            iz: height * width.powi(3) / 12.0,
            torsion,
        }
    }
}

/// The 12 × 12 stiffness of an element from `a` to `b` (m) in global axes. The section's local
/// y axis is the part of `up` orthogonal to the element (so `up` must not be parallel to it);
/// local z is x × y.
pub fn frame_stiffness(
    a: [f64; 3],
    b: [f64; 3],
    up: [f64; 3],
    s: &FrameSection,
) -> Result<Mat<f64>> {
    let (rot, l) = local_axes(a, b, up)?;
    let (e, g) = (s.youngs_modulus, s.shear_modulus);
    let mut k = Mat::<f64>::zeros(12, 12);
    let mut put = |i: usize, j: usize, v: f64| {
        k[(i, j)] += v;
        if i != j {
            k[(j, i)] += v;
        }
    };
    // Local DOF: u1 v1 w1 θx1 θy1 θz1 | u2 v2 w2 θx2 θy2 θz2.
    let ea = e * s.area / l;
    put(0, 0, ea);
    put(6, 6, ea);
    put(0, 6, -ea);
    let gj = g * s.torsion / l;
    put(3, 3, gj);
    put(9, 9, gj);
    put(3, 9, -gj);
    // Bending in the x-y plane (v, θz), EI_z.
    let c = e * s.iz / (l * l * l);
    for &(i, j, v) in &[
        (1, 1, 12.0),
        (1, 5, 6.0 * l),
        (1, 7, -12.0),
        (1, 11, 6.0 * l),
        (5, 5, 4.0 * l * l),
        (5, 7, -6.0 * l),
        (5, 11, 2.0 * l * l),
        (7, 7, 12.0),
        (7, 11, -6.0 * l),
        (11, 11, 4.0 * l * l),
    ] {
        put(i, j, c * v);
    }
    // Bending in the x-z plane (w, θy), EI_y: θy = −dw/dx flips the coupling signs.
    let c = e * s.iy / (l * l * l);
    for &(i, j, v) in &[
        (2, 2, 12.0),
        (2, 4, -6.0 * l),
        (2, 8, -12.0),
        (2, 10, -6.0 * l),
        (4, 4, 4.0 * l * l),
        (4, 8, 6.0 * l),
        (4, 10, 2.0 * l * l),
        (8, 8, 12.0),
        (8, 10, 6.0 * l),
        (10, 10, 4.0 * l * l),
    ] {
        put(i, j, c * v);
    }
    // Global: K = Tᵀ K_local T with T = diag(R, R, R, R), rows of R the local axes.
    let t = Mat::<f64>::from_fn(12, 12, |i, j| {
        if i / 3 == j / 3 {
            rot[i % 3][j % 3]
        } else {
            0.0
        }
    });
    Ok(t.transpose() * &k * &t)
}

/// Local axes (rows: x along the element, y, z) and the length.
fn local_axes(a: [f64; 3], b: [f64; 3], up: [f64; 3]) -> Result<([[f64; 3]; 3], f64)> {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let bad = |why: &'static str| -> Error {
        MeshError::DegenerateElement {
            from: a,
            to: b,
            why,
        }
        .into()
    };
    if !(l > 0.0 && l.is_finite()) {
        return Err(bad("zero length"));
    }
    let x = d.map(|v| v / l);
    let dot = up[0] * x[0] + up[1] * x[1] + up[2] * x[2];
    let y = [up[0] - dot * x[0], up[1] - dot * x[1], up[2] - dot * x[2]];
    let ny = (y[0] * y[0] + y[1] * y[1] + y[2] * y[2]).sqrt();
    if ny < 1e-9 * (up[0].abs() + up[1].abs() + up[2].abs()).max(f64::MIN_POSITIVE) {
        return Err(bad("the `up` vector is parallel to the element"));
    }
    let y = y.map(|v| v / ny);
    let z = [
        x[1] * y[2] - x[2] * y[1],
        x[2] * y[0] - x[0] * y[2],
        x[0] * y[1] - x[1] * y[0],
    ];
    Ok(([x, y, z], l))
}

/// The rotary inertia one end of an element carries, about the global x, y, z axes
/// (kg·m²): in local axes the half element's polar inertia $\rho (I_y + I_z) L / 2$ about its
/// axis and $\rho I L / 2 + \rho A L^3 / 24$ (section plus the half's mass about the node)
/// about each transverse axis, rotated to global axes, of which the lumped mass keeps the
/// diagonal (exact for elements along a global axis).
fn rotary_inertia_diagonal(
    a: [f64; 3],
    b: [f64; 3],
    up: [f64; 3],
    s: &FrameSection,
) -> Result<[f64; 3]> {
    let (rot, l) = local_axes(a, b, up)?;
    let rho = s.density;
    let transverse = rho * s.area * l.powi(3) / 24.0;
    let local = [
        rho * (s.iy + s.iz) * l / 2.0,
        rho * s.iy * l / 2.0 + transverse,
        rho * s.iz * l / 2.0 + transverse,
    ];
    // J_global = Rᵀ diag(local) R, rows of R the local axes: diagonal entry g is
    // Σ_k local_k R[k][g]².
    Ok([0, 1, 2].map(|g| (0..3).map(|k| local[k] * rot[k][g] * rot[k][g]).sum()))
}

/// A frame body: nodes, elements as 0-based node pairs with their `up` vectors, one section,
/// in any consistent units (m–kg–s with Pa, or mm–t–s with N/mm²). Six DOF per node. Lumped
/// mass: each end of an element gets half its mass $\rho A L / 2$ on x, y, z and on the
/// rotations the diagonal of its rotary inertia (see `rotary_inertia_diagonal`).
pub fn frame(
    name: &str,
    nodes: Vec<[f64; 3]>,
    elements: &[([usize; 2], [f64; 3])],
    section: &FrameSection,
) -> Result<FeModel> {
    let sectioned: Vec<([usize; 2], [f64; 3], usize)> =
        elements.iter().map(|&(e, up)| (e, up, 0)).collect();
    frame_of_sections(name, nodes, &sectioned, std::slice::from_ref(section))
}

/// [`frame`] with several sections: each element names its section by index into
/// `sections`.
pub fn frame_of_sections(
    name: &str,
    nodes: Vec<[f64; 3]>,
    elements: &[([usize; 2], [f64; 3], usize)],
    sections: &[FrameSection],
) -> Result<FeModel> {
    let dofs = DofMap::frame_3d();
    let per = dofs.per_node();
    let n = nodes.len();
    for &([i, j], _, sec) in elements {
        if sec >= sections.len() {
            return Err(MeshError::SectionOutOfRange {
                body: name.into(),
                section: sec,
                sections: sections.len(),
            }
            .into());
        }
        if i >= n || j >= n {
            return Err(Error::NodeOutOfRange {
                node: NodeIndex(i.max(j)).number(),
                count: n,
                body: name.into(),
            });
        }
    }
    let connectivity: Vec<[usize; 2]> = elements.iter().map(|(e, _, _)| *e).collect();
    let pattern = SparsityPattern::from_elements(n, per, connectivity.iter().map(|c| c.as_slice()));
    let mut k = SparseAssembly::new(pattern);
    let mut m = vec![0.0; n * per];
    for &([i, j], up, sec) in elements {
        let section = &sections[sec];
        let ke = frame_stiffness(nodes[i], nodes[j], up, section)?;
        let element_dofs: Vec<usize> = [i, j]
            .iter()
            .flat_map(|&node| (0..per).map(move |d| node * per + d))
            .collect();
        k.add_element(&element_dofs, ke.as_ref());
        let l = (0..3)
            .map(|a| (nodes[j][a] - nodes[i][a]).powi(2))
            .sum::<f64>()
            .sqrt();
        let half = 0.5 * section.density * section.area * l;
        let rotary = rotary_inertia_diagonal(nodes[i], nodes[j], up, section)?;
        for node in [i, j] {
            for a in 0..3 {
                m[node * per + a] += half;
                m[node * per + 3 + a] += rotary[a];
            }
        }
    }
    Ok(FeModel {
        name: name.into(),
        dofs,
        nodes,
        edges: connectivity,
        k: k.finish(),
        m: MassMatrix::Lumped(m),
        rigid_motions: RigidMotions::FromGeometry,
    })
}
