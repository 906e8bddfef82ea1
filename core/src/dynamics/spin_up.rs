//! A prescribed spin-up about a fixed axis: the frame turns from rest to a steady rate Ω over a
//! ramp time $T$ with a smooth angular acceleration,
//! $$\ddot\theta = \frac{\Omega}{T}\left(1 - \cos\frac{2\pi t}{T}\right)\ (t \le T),\quad
//! \dot\theta = \Omega\left(\frac tT - \frac{1}{2\pi}\sin\frac{2\pi t}{T}\right),\quad
//! \theta = \Omega\left(\frac{t^2}{2T} + \frac{T}{4\pi^2}\left(\cos\frac{2\pi t}{T} - 1
//! \right)\right),$$
//! then $\dot\theta = \Omega$. The acceleration starts and ends at zero, so the spin-up
//! excites the elastic modes little: the classic spin-up manoeuvre of flexible multibody
//! benchmarks (a beam spun up about one end).

use nalgebra::{Rotation3, Unit, Vector3};

/// A spin-up about a fixed unit axis through the frame's origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinUp {
    /// The axis, a unit vector in the body frame (equal to the ground frame at t = 0).
    pub axis: Unit<Vector3<f64>>,
    /// Steady rate Ω, rad/s.
    pub rate: f64,
    /// Ramp time T, s (> 0).
    pub ramp: f64,
}

impl SpinUp {
    /// $(\theta, \dot\theta, \ddot\theta)$ at time `t` (rad, rad/s, rad/s²).
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        let (w, big_t) = (self.rate, self.ramp);
        if t <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let two_pi = 2.0 * std::f64::consts::PI;
        if t >= big_t {
            return (w * big_t / 2.0 + w * (t - big_t), w, 0.0);
        }
        let phase = two_pi * t / big_t;
        let theta = w * (t * t / (2.0 * big_t) + big_t / (two_pi * two_pi) * (phase.cos() - 1.0));
        let rate = w * (t / big_t - phase.sin() / two_pi);
        let acceleration = w / big_t * (1.0 - phase.cos());
        (theta, rate, acceleration)
    }

    /// The frame's orientation at `t`: body to ground.
    pub fn rotation(&self, t: f64) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&self.axis, self.at(t).0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The angle and rate are the integrals of the rate and acceleration (Simpson's rule on a
    /// fine grid), continuous at the end of the ramp.
    #[test]
    fn derivatives_integrate_to_the_angle_and_rate() {
        let s = SpinUp {
            axis: Vector3::z_axis(),
            rate: 30.0,
            ramp: 0.4,
        };
        let n = 2000;
        for end in [0.13, 0.4, 0.55] {
            let h = end / n as f64;
            let simpson = |f: &dyn Fn(f64) -> f64| {
                (0..n)
                    .map(|i| {
                        let a = i as f64 * h;
                        h / 6.0 * (f(a) + 4.0 * f(a + h / 2.0) + f(a + h))
                    })
                    .sum::<f64>()
            };
            let (theta, rate, _) = s.at(end);
            assert!((simpson(&|t| s.at(t).1) - theta).abs() < 1e-9 * theta.max(1.0));
            assert!((simpson(&|t| s.at(t).2) - rate).abs() < 1e-9 * rate.max(1.0));
        }
        let (a, b) = (s.at(0.4 - 1e-12), s.at(0.4 + 1e-12));
        assert!((a.0 - b.0).abs() < 1e-9 && (a.1 - b.1).abs() < 1e-9 && a.2.abs() < 1e-9);
    }
}
