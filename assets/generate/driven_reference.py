#!/usr/bin/env python3
"""Reference values for a body driven through a rigid interface, computed by SciPy alone.

The body (a committed body file: Matrix Market K and M, node coordinates, node sets) spins up
about an axis through the centroid of the driven node set, that set clamped in the turning
frame. In the frame, with E = I (x) skew(e) and H = M E E, G = M E (M is the same on the three
directions of a node), Lagrange's equations of the nodal displacements u are

    M u'' + 2 w G u' + (K + w' G + w^2 H) u = -w' G s - w^2 H s,

w(t) the spin rate. This script builds G and H with scipy.sparse (Kronecker products), then

* `clamped_hz`: the lowest natural frequencies with the set clamped (eigsh, shift-invert);
* `steady`: the steady state at the final rate, (K + W^2 H) u = -W^2 H s (spsolve), as the
  mean displacement of each output set;
* `modal_history`: the equations projected on the `modes` lowest clamped modes, integrated by
  DOP853 (rtol 1e-11) from rest, sampled at `times`: the mean displacement of each output set;
* `steady_orbit`: the steady state when the axis passes through `orbit_point` instead (the
  positions s measured from that point);
* `steady_mean_axes`: the steady spin seen from the body's mean axes, u - P (P^T M P)^-1 P^T M u
  with P the rigid-body modes;
* `steady_pinned`: the steady spin with the other output set pinned (its ring turns rigidly
  about its centroid, which keeps its place in the frame), at the node farthest from the drive's
  centroid (`pinned_output_node`, 1-based);
* `gravity_static`: the static deflection under gravity `gravity` (m/s^2, the body in m),
  K u = M (1 (x) g).

Usage: driven_reference.py BODY_DIR --drive SET --out FILE [--rate W --ramp T --end T_END
       --modes N --axis X Y Z]
"""

import argparse
import gzip
import json
import pathlib
import tomllib

import numpy as np
import scipy.io
import scipy.sparse as sp
import scipy.sparse.linalg as sla
from scipy.integrate import solve_ivp


def read_mtx(path):
    opener = gzip.open if str(path).endswith(".gz") else open
    with opener(path, "rb") as f:
        return sp.csc_matrix(scipy.io.mmread(f))


def spin(t, rate, ramp):
    """Rate and angular acceleration of the spin-up (the acceleration a raised cosine)."""
    if t >= ramp:
        return rate, 0.0
    phase = 2 * np.pi * t / ramp
    return rate * (t / ramp - np.sin(phase) / (2 * np.pi)), rate / ramp * (1 - np.cos(phase))


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("body", type=pathlib.Path)
    p.add_argument("--drive", required=True)
    p.add_argument("--out", required=True, type=pathlib.Path)
    p.add_argument("--rate", type=float, default=100.0)
    p.add_argument("--ramp", type=float, default=0.1)
    p.add_argument("--end", type=float, default=0.2)
    p.add_argument("--modes", type=int, default=20)
    p.add_argument("--axis", type=float, nargs=3, default=[0.0, 0.0, 1.0])
    args = p.parse_args()

    spec = tomllib.loads((args.body / "body.toml").read_text())
    k = read_mtx(args.body / spec["matrices"]["stiffness"])
    m = read_mtx(args.body / spec["matrices"]["mass"])
    nodes = np.loadtxt(args.body / spec["geometry"]["nodes"], delimiter=",", comments="#")
    order = np.argsort(nodes[:, 0])
    xyz = nodes[order, 1:4]
    n = k.shape[0]
    sets = spec["node_sets"]
    ring = np.array(sets[args.drive]) - 1
    master = xyz[ring].mean(axis=0)
    s = (xyz - master).reshape(-1)
    clamped = np.zeros(n, dtype=bool)
    for a in range(3):
        clamped[3 * ring + a] = True
    free = np.flatnonzero(~clamped)

    e = np.array(args.axis) / np.linalg.norm(args.axis)
    skew = np.array([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    big_e = sp.kron(sp.identity(n // 3), sp.csr_matrix(skew), format="csc")
    g = (m @ big_e).tocsc()
    h = (m @ big_e @ big_e).tocsc()
    kff = k[free][:, free]
    mff = m[free][:, free]
    gff = g[free][:, free]
    hff = h[free][:, free]
    gs = (g @ s)[free]
    hs = (h @ s)[free]

    outputs = sorted(name for name in sets if name != args.drive)

    def means(u_free):
        u = np.zeros(n)
        u[free] = u_free
        out = {}
        for name in outputs:
            idx = np.array(sets[name]) - 1
            out[name] = [float(u[3 * idx + a].mean()) for a in range(3)]
        return out

    lam, phi = sla.eigsh(kff, k=args.modes, M=mff, sigma=0.0, which="LM")
    order = np.argsort(lam)
    lam, phi = lam[order], phi[:, order]
    hz = np.sqrt(lam) / (2 * np.pi)

    w = args.rate
    steady = spla_solve(kff + w * w * hff, -w * w * hs)
    orbit_point = np.array([-0.2, 0.0, 0.0])
    s_orbit = (xyz - orbit_point).reshape(-1)
    steady_orbit = spla_solve(kff + w * w * hff, -w * w * (h @ s_orbit)[free])
    full = np.zeros(n)
    full[free] = steady
    centre = (xyz * np.asarray(m.sum(axis=1)).reshape(-1, 3)).sum(axis=0) / m.sum() * 3
    rel = xyz - centre
    p_rigid = np.zeros((n, 6))
    for a in range(3):
        p_rigid[a::3, a] = 1.0
        axis_a = np.eye(3)[a]
        p_rigid[:, 3 + a] = np.cross(axis_a, rel).reshape(-1)
    mp = m @ p_rigid
    q = np.linalg.solve(p_rigid.T @ mp, mp.T @ full)
    steady_mean = (full - p_rigid @ q)[free]
    # Pinned: u = T x, x = (free DOF outside both rings, the pinned ring's three rotations).
    pin_name = outputs[0]
    pin = np.array(sets[pin_name]) - 1
    pin_centre = xyz[pin].mean(axis=0)
    pinned_dofs = np.concatenate([3 * pin + a for a in range(3)])
    keep = np.ones(n, dtype=bool)
    keep[clamped] = False
    keep[pinned_dofs] = False
    free_p = np.flatnonzero(keep)
    t_rows, t_cols, t_vals = [], [], []
    for i, d in enumerate(free_p):
        t_rows.append(d)
        t_cols.append(i)
        t_vals.append(1.0)
    base = len(free_p)
    for j in pin:
        r = xyz[j] - pin_centre
        for q in range(3):
            col = np.cross(np.eye(3)[q], r)
            for a in range(3):
                t_rows.append(3 * j + a)
                t_cols.append(base + q)
                t_vals.append(col[a])
    tmat = sp.csc_matrix((t_vals, (t_rows, t_cols)), shape=(n, base + 3))
    x_p = spla_solve(tmat.T @ (k + w * w * h) @ tmat, -w * w * (tmat.T @ (h @ s)))
    u_p = tmat @ x_p
    far = int(np.argmax(((xyz - master) ** 2).sum(axis=1)))
    gravity = np.array([0.0, 0.0, -9.81])
    g_load = (m @ np.tile(gravity, n // 3))[free]
    gravity_static = spla_solve(kff, g_load)

    # Modal equations, mass-normalised modes: q'' + 2w g q' + (L + w' g + w^2 h) q = f.
    gm = phi.T @ (gff @ phi)
    hm = phi.T @ (hff @ phi)
    gsm = phi.T @ gs
    hsm = phi.T @ hs
    nm = args.modes

    def rhs(t, y):
        q, qd = y[:nm], y[nm:]
        rate, acc = spin(t, args.rate, args.ramp)
        qdd = -2 * rate * (gm @ qd) - lam * q - acc * (gm @ q) - rate * rate * (hm @ q)
        qdd -= acc * gsm + rate * rate * hsm
        return np.concatenate([qd, qdd])

    times = np.linspace(0.0, args.end, 9)
    sol = solve_ivp(rhs, (0.0, args.end), np.zeros(2 * nm), method="DOP853", t_eval=times,
                    rtol=1e-11, atol=1e-18)
    assert sol.success, sol.message
    history = [means(phi @ sol.y[:nm, i]) for i in range(len(times))]

    out = {
        "generator": "assets/generate/driven_reference.py (SciPy %s, NumPy %s)"
        % (scipy.__version__, np.__version__),
        "drive": args.drive,
        "axis": e.tolist(),
        "rate": args.rate,
        "ramp": args.ramp,
        "end": args.end,
        "outputs": outputs,
        "clamped_hz": hz[:10].tolist(),
        "steady": means(steady),
        "orbit_point": orbit_point.tolist(),
        "steady_orbit": means(steady_orbit),
        "steady_mean_axes": means(steady_mean),
        "pinned": pin_name,
        "pinned_output_node": far + 1,
        "steady_pinned": [float(u_p[3 * far + a]) for a in range(3)],
        "gravity": gravity.tolist(),
        "gravity_static": means(gravity_static),
        "modal_modes": nm,
        "modal_times": times.tolist(),
        "modal_history": history,
    }
    args.out.write_text(json.dumps(out, indent=1) + "\n")
    print("wrote", args.out, "clamped Hz", np.round(hz[:4], 4), "steady", out["steady"])


def spla_solve(a, b):
    return sla.spsolve(a.tocsc(), b)


if __name__ == "__main__":
    main()
