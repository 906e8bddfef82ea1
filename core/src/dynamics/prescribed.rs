//! Prescribed motion of a nodal coordinate: position, velocity and acceleration over time.

/// A time function $x(t)$ with its derivatives, m, m/s, m/s².
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// Held where it starts.
    Fixed,
    /// Eq. (7.10), one component: $\ddot x = -a(\cos\Omega t + c_2\cos 2\Omega t)$ (`sine =
    /// false`) or $-a(\sin\Omega t + c_2 \sin 2\Omega t)$ (`sine = true`), integrated from the
    /// given initial position and velocity.
    Harmonic {
        /// $a = R\Omega^2$, m/s².
        a: f64,
        /// Ω, rad/s.
        omega: f64,
        /// Coefficient of the second harmonic.
        c2: f64,
        /// Sine instead of cosine.
        sine: bool,
    },
    /// Accelerations sampled every `dt` seconds, linearly interpolated (§7.2.4), integrated
    /// exactly (piecewise cubic position). Held at the last value past the end.
    Table {
        /// Sampling interval, s.
        dt: f64,
        /// Accelerations, m/s².
        values: Vec<f64>,
        /// Position and velocity gained from the accelerations alone at each sample.
        knots: Vec<(f64, f64)>,
    },
}

impl Motion {
    /// A table of accelerations sampled every `dt` seconds.
    pub fn table(dt: f64, values: Vec<f64>) -> Self {
        let mut knots = Vec::with_capacity(values.len());
        let (mut x, mut v) = (0.0, 0.0);
        knots.push((x, v));
        for w in values.windows(2) {
            x += v * dt + w[0] * dt * dt / 2.0 + (w[1] - w[0]) * dt * dt / 6.0;
            v += (w[0] + w[1]) * dt / 2.0;
            knots.push((x, v));
        }
        Motion::Table { dt, values, knots }
    }

    /// `(x, v, a)` at time `t` for the initial position `x0` and velocity `v0`.
    pub fn at(&self, t: f64, x0: f64, v0: f64) -> (f64, f64, f64) {
        match self {
            Motion::Fixed => (x0, 0.0, 0.0),
            Motion::Harmonic { a, omega, c2, sine } => {
                let (w, w2) = (*omega, 2.0 * omega);
                if *sine {
                    // a(t) = -a (sin wt + c2 sin 2wt)
                    let acc = -a * ((w * t).sin() + c2 * (w2 * t).sin());
                    let vel = a * ((w * t).cos() / w + c2 * (w2 * t).cos() / w2)
                        - a * (1.0 / w + c2 / w2)
                        + v0;
                    let pos = a * ((w * t).sin() / (w * w) + c2 * (w2 * t).sin() / (w2 * w2))
                        - a * (1.0 / w + c2 / w2) * t
                        + v0 * t
                        + x0;
                    (pos, vel, acc)
                } else {
                    let acc = -a * ((w * t).cos() + c2 * (w2 * t).cos());
                    let vel = -a * ((w * t).sin() / w + c2 * (w2 * t).sin() / w2) + v0;
                    let pos = a * ((w * t).cos() / (w * w) + c2 * (w2 * t).cos() / (w2 * w2))
                        - a * (1.0 / (w * w) + c2 / (w2 * w2))
                        + v0 * t
                        + x0;
                    (pos, vel, acc)
                }
            }
            Motion::Table { dt, values, knots } => {
                if values.is_empty() {
                    return (x0 + v0 * t, v0, 0.0);
                }
                let last = values.len() - 1;
                let i = ((t / dt).floor().max(0.0) as usize).min(last);
                let h = t - i as f64 * dt;
                let (xk, vk) = knots[i];
                let a0 = values[i];
                let slope = if i < last {
                    (values[i + 1] - a0) / dt
                } else {
                    0.0
                };
                let h = if i < last { h.min(*dt) } else { h };
                let acc = a0 + slope * h;
                let x = x0 + v0 * t + xk + vk * h + a0 * h * h / 2.0 + slope * h * h * h / 6.0;
                let v = v0 + vk + a0 * h + slope * h * h / 2.0;
                (x, v, acc)
            }
        }
    }
}
