#!/usr/bin/env python3
"""Independent references for a spinning cantilever, computed without flexmodes' elements.

1. `campbell`: the clamped-free Euler-Bernoulli beam spinning about an axis through its root
   (hub radius r = R L), flapwise bending, by Rayleigh-Ritz on polynomials (x^2 times shifted
   Legendre polynomials, degree up to `--degree`, Gauss-Legendre quadrature), dimensionless:

       (w'')'' - (n w')' = mu^2 w,   n(x) = lambda^2 ((1 + R)^2 - (R + x)^2) / 2,

   mu = omega sqrt(rho A L^4 / EI), lambda = Omega sqrt(rho A L^4 / EI). The lagwise
   frequencies (in the plane of rotation, Coriolis coupling to the axial motion left out, as in
   the published tables) are sqrt(mu_flap^2 - lambda^2). Written for lambda = 0..12 with and
   without the centrifugal tension n (without it the flapwise frequency stays at rest and the
   lagwise one reaches zero at lambda = mu_1).

2. `spin_up`: Kane, Ryan and Banerjee's (1987) beam spun up about its root, theta(t) =
   (ws/Ts)(t^2/2 + (Ts/2pi)^2 (cos(2 pi t/Ts) - 1)) for t < Ts, then at ws, by a geometrically
   nonlinear planar co-rotational beam (Crisfield's element: linear local strains, exact rigid
   rotations; lumped translational mass), in ground axes, Newmark's scheme with slight
   numerical damping and Newton iterations on the consistent tangent. The tip's transverse
   deflection in the hub frame, y_hub = -sin(theta) X + cos(theta) Y, is written every
   `--every` steps.

Usage: spinning_beam_reference.py --out DIR [--elements 40 --step 1e-3 --every 50 --degree 18]
(about 25 min per rate with the defaults; the committed files were written with them)
"""

import argparse
import math
import pathlib

import numpy as np
import scipy.linalg as la


# ---------------------------------------------------------------- 1. Campbell (Rayleigh-Ritz)
def ritz_basis(degree, x):
    """phi_k = x^2 P_k(2x - 1) and its first two derivatives at points x, k = 0..degree."""
    t = 2 * x - 1
    p = np.zeros((degree + 1, x.size))
    dp = np.zeros_like(p)
    d2p = np.zeros_like(p)
    for k in range(degree + 1):
        c = np.zeros(k + 1)
        c[k] = 1.0
        leg = np.polynomial.legendre.Legendre(c)
        p[k] = leg(t)
        dp[k] = 2 * leg.deriv(1)(t)
        d2p[k] = 4 * leg.deriv(2)(t)
    phi = x**2 * p
    dphi = 2 * x * p + x**2 * dp
    d2phi = 2 * p + 4 * x * dp + x**2 * d2p
    return phi, dphi, d2phi


def flap_frequencies(lam, hub, degree, count, stiffening=True):
    g, w = np.polynomial.legendre.leggauss(4 * degree + 8)
    x = 0.5 * (g + 1)
    w = 0.5 * w
    phi, dphi, d2phi = ritz_basis(degree, x)
    n = 0.5 * lam**2 * ((1 + hub) ** 2 - (hub + x) ** 2) if stiffening else 0 * x
    m = (phi * w) @ phi.T
    k = (d2phi * w) @ d2phi.T + (dphi * (w * n)) @ dphi.T
    mu2 = la.eigh(k, m, eigvals_only=True)
    return np.sqrt(mu2[:count])


# ------------------------------------------------- 2. Kane's spin-up (co-rotational, Newmark)
def spin(t, ws, ts):
    if t >= ts:
        return ws * ts / 2 + ws * (t - ts), ws, 0.0
    ph = 2 * math.pi * t / ts
    th = ws / ts * (t * t / 2 + (ts / (2 * math.pi)) ** 2 * (math.cos(ph) - 1))
    return th, ws * (t / ts - math.sin(ph) / (2 * math.pi)), ws / ts * (1 - math.cos(ph))


def wrap(a):
    return math.atan2(math.sin(a), math.cos(a))


def element(xa, xb, pa, pb, l0, ea, ei):
    """Internal force (6) and tangent (6x6) of a co-rotational element, DOF (X, Y, phi) x 2."""
    dx, dy = xb[0] - xa[0], xb[1] - xa[1]
    l = math.hypot(dx, dy)
    c, s = dx / l, dy / l
    beta = math.atan2(dy, dx)
    t1, t2 = wrap(pa - beta), wrap(pb - beta)
    u = l - l0
    nf = ea * u / l0
    m1 = ei / l0 * (4 * t1 + 2 * t2)
    m2 = ei / l0 * (2 * t1 + 4 * t2)
    r = np.array([-c, -s, 0.0, c, s, 0.0])
    z = np.array([s, -c, 0.0, -s, c, 0.0])
    b = np.vstack([r, np.array([0, 0, 1.0, 0, 0, 0]) - z / l, np.array([0, 0, 0, 0, 0, 1.0]) - z / l])
    d = np.array([[ea / l0, 0, 0], [0, 4 * ei / l0, 2 * ei / l0], [0, 2 * ei / l0, 4 * ei / l0]])
    f = b.T @ np.array([nf, m1, m2])
    kt = b.T @ d @ b + nf / l * np.outer(z, z) + (m1 + m2) / l**2 * (np.outer(r, z) + np.outer(z, r))
    return f, kt


def kane_spin_up(ws, ts, end, length, ei, ea, rho_a, elements, step, every, damping):
    nn = elements + 1
    le = length / elements
    x0 = np.zeros(3 * nn)
    x0[0::3] = np.arange(nn) * le
    mass = np.zeros(3 * nn)
    for e in range(elements):
        for node in (e, e + 1):
            mass[3 * node] += 0.5 * rho_a * le
            mass[3 * node + 1] += 0.5 * rho_a * le
    free = np.arange(3, 3 * nn)
    gamma = 0.5 + damping
    beta = (1 + damping) ** 2 / 4
    h = step

    def root(t):
        th, w, a = spin(t, ws, ts)
        return th, w, a

    def forces(q):
        f = np.zeros(3 * nn)
        k = np.zeros((3 * nn, 3 * nn))
        for e in range(elements):
            dofs = np.arange(3 * e, 3 * e + 6)
            xa = (q[3 * e], q[3 * e + 1])
            xb = (q[3 * e + 3], q[3 * e + 4])
            fe, ke = element(xa, xb, q[3 * e + 2], q[3 * e + 5], le, ea, ei)
            f[dofs] += fe
            k[np.ix_(dofs, dofs)] += ke
        return f, k

    q = x0.copy()
    v = np.zeros(3 * nn)
    a = np.zeros(3 * nn)
    out = [(0.0, 0.0)]
    count = int(round(end / h))
    for n in range(1, count + 1):
        t = n * h
        th, w, al = root(t)
        qp = q + h * v + h * h * (0.5 - beta) * a
        vp = v + h * (1 - gamma) * a
        qn = qp.copy()
        # The root: clamped at the hub, turned by theta(t).
        qn[0:3] = (0.0, 0.0, th)
        an = (qn - qp) / (beta * h * h)
        for it in range(30):
            f, k = forces(qn)
            rf = (mass * an + f)[free]
            keff = k[np.ix_(free, free)] + np.diag(mass[free]) / (beta * h * h)
            dq = np.linalg.solve(keff, -rf)
            qn[free] += dq
            an = (qn - qp) / (beta * h * h)
            # Converged when the correction is at round-off of the positions (1e-12 L).
            if np.abs(dq).max() <= 1e-12 * length:
                break
        else:
            raise RuntimeError(f"Newton did not converge at t = {t}: |dq| {np.abs(dq).max()}")
        vn = vp + gamma * h * an
        q, v, a = qn, vn, an
        if n % every == 0:
            tx, ty = q[-3], q[-2]
            out.append((t, -math.sin(th) * tx + math.cos(th) * ty))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--elements", type=int, default=40)
    ap.add_argument("--step", type=float, default=1e-3)
    ap.add_argument("--every", type=int, default=50)
    ap.add_argument("--degree", type=int, default=18)
    ap.add_argument("--damping", type=float, default=0.02)
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)

    rows = ["lambda,flap1,flap2,lag1,lag2,flap1_unstiffened,lag1_unstiffened"]
    mu0 = flap_frequencies(0.0, 0.0, args.degree, 2)
    for lam in range(0, 13):
        fl = flap_frequencies(float(lam), 0.0, args.degree, 2)
        lag = np.sqrt(np.maximum(fl**2 - lam**2, 0.0))
        lag_u = math.sqrt(max(mu0[0] ** 2 - lam**2, 0.0))
        rows.append(f"{lam},{fl[0]:.8f},{fl[1]:.8f},{lag[0]:.8f},{lag[1]:.8f},{mu0[0]:.8f},{lag_u:.8f}")
    (out / "campbell-ritz.csv").write_text("\n".join(rows) + "\n")
    print("\n".join(rows))

    # Kane et al. (1987): L = 10 m, EI = 14 000 N m^2, rho A = 1.2 kg/m, EA = 2.8e7 N.
    for ws in (4.0, 10.0):
        hist = kane_spin_up(ws, 15.0, 20.0, 10.0, 1.4e4, 2.8e7, 1.2, args.elements, args.step,
                            args.every, args.damping)
        lines = ["time_s,tip_deflection_m"] + [f"{t:.4f},{y:.9e}" for t, y in hist]
        (out / f"kane-spin-up-{int(ws)}.csv").write_text("\n".join(lines) + "\n")
        peak = max(abs(y) for _, y in hist)
        print(f"ws = {ws}: peak |tip deflection| {peak:.6f} m, final {hist[-1][1]:.6f} m")


if __name__ == "__main__":
    main()
