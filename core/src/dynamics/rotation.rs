//! Euler parameters (§2.1.2) and small rotation helpers.

use nalgebra::{Matrix3, Matrix3x4, Vector3, Vector4};

/// $\tilde a$, the cross-product matrix: $\tilde a b = a \times b$.
pub fn skew(a: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// $A = (2e_0^2 - 1)I + 2(ee^T + e_0\tilde e)$ (Eq. 2.7).
pub fn rotation_matrix(p: &Vector4<f64>) -> Matrix3<f64> {
    let e0 = p[0];
    let e = Vector3::new(p[1], p[2], p[3]);
    Matrix3::identity() * (2.0 * e0 * e0 - 1.0) + 2.0 * (e * e.transpose() + e0 * skew(&e))
}

/// $L = [-e,\ -\tilde e + e_0 I]$ (Eq. 2.15); $\dot p = \tfrac12 L^T \bar\omega$ (Eq. 2.14).
pub fn l_matrix(p: &Vector4<f64>) -> Matrix3x4<f64> {
    let e0 = p[0];
    let e = Vector3::new(p[1], p[2], p[3]);
    let b = -skew(&e) + Matrix3::identity() * e0;
    Matrix3x4::from_columns(&[
        -e,
        b.column(0).into(),
        b.column(1).into(),
        b.column(2).into(),
    ])
}

/// Euler parameters of a rotation matrix (Shepperd's method), $e_0 \ge 0$.
pub fn euler_parameters_from_matrix(a: &Matrix3<f64>) -> Vector4<f64> {
    let q = nalgebra::UnitQuaternion::from_matrix(a);
    let mut p = Vector4::new(q.w, q.i, q.j, q.k);
    if p[0] < 0.0 {
        p = -p;
    }
    p
}

/// Rotates the frame `p` by a small rotation vector `theta` given in body components.
pub fn rotate_body(p: &Vector4<f64>, theta: &Vector3<f64>) -> Vector4<f64> {
    let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        p[0], p[1], p[2], p[3],
    ));
    let dq = nalgebra::UnitQuaternion::from_scaled_axis(*theta);
    let r = q * dq;
    Vector4::new(r.w, r.i, r.j, r.k)
}
