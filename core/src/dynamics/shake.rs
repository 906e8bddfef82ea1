//! A prescribed harmonic translation of the frame's origin, $r(t) = a \sin(2\pi f t)\,d$:
//! it starts at rest in acceleration ($\ddot r(0) = 0$) with the velocity $2\pi f a\,d$ the
//! body already has, so the start excites nothing but what the shaking does.

use nalgebra::{Unit, Vector3};

/// A harmonic translation along a fixed direction (ground axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shake {
    /// The direction, a unit vector in ground axes.
    pub direction: Unit<Vector3<f64>>,
    /// Amplitude a, in the body's length unit.
    pub amplitude: f64,
    /// Frequency f, Hz.
    pub frequency: f64,
}

impl Shake {
    /// $\ddot r(t)$ in ground axes (length unit per s²).
    pub fn acceleration(&self, t: f64) -> Vector3<f64> {
        let w = 2.0 * std::f64::consts::PI * self.frequency;
        self.direction.into_inner() * (-self.amplitude * w * w * (w * t).sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The acceleration is the second derivative of a sin(2πft) (central differences).
    #[test]
    fn the_acceleration_is_the_second_derivative_of_the_motion() {
        let s = Shake {
            direction: Vector3::x_axis(),
            amplitude: 2e-3,
            frequency: 35.0,
        };
        let r = |t: f64| s.amplitude * (2.0 * std::f64::consts::PI * s.frequency * t).sin();
        for t in [0.0, 0.003, 0.011, 0.02] {
            let h = 1e-5;
            let fd = (r(t + h) - 2.0 * r(t) + r(t - h)) / (h * h);
            let a = s.acceleration(t).x;
            assert!((fd - a).abs() < 1e-5 * (2.0 * std::f64::consts::PI * 35.0f64).powi(2) * 2e-3);
        }
    }
}
