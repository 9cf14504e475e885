#!/usr/bin/env python3
"""Stability of the explicit solver's contact sub-cycling (docs/physics.md §4 "Contact
sub-cycling") on a 1-D model: two bars of N_ELEMENTS lumped-mass elements (k = m = 1, so the
cells' omega_mesh = 2), the second fixed at its far end, joined by a penalty spring with dashpot
between the first bar's end node and the second bar's first node (omega_p = ratio x omega_mesh
over their reduced mass, damping zeta of critical). The two contact nodes take N sub-steps of the
leap-frog with the penalty force, their internal force acting as the step's impulse dt M^-1 f at
the start of the step (the impulse form); every other node takes the step dt. For each
(zeta, ratio, N) it prints the first dt (in units of 2 / omega_mesh, on a grid of step 0.004)
where the step's amplification matrix has an eigenvalue above 1, and that dt over the bound
min(0.95, 1.75 / (2 ratio)) that the solver uses ('-': stable up to 1).
The 'hold' variant (the internal force held at every sub-step) is unstable at every dt.
Usage: scripts/subcycle_stability.py [N_ELEMENTS (default 6)] [hold]   (needs numpy)
"""
import sys

import numpy as np


def system(n, ratio, zeta):
    size = 2 * (n + 1)
    k, m = np.zeros((size, size)), np.zeros(size)
    for off in (0, n + 1):
        for e in range(n):
            i, j = off + e, off + e + 1
            k[np.ix_([i, j], [i, j])] += [[1, -1], [-1, 1]]
            m[[i, j]] += 0.5
    s, w = n, n + 1
    m_red = 1 / (1 / m[s] + 1 / m[w])
    kp = (ratio * 2.0) ** 2 * m_red
    pen = np.zeros((size, size))
    pen[np.ix_([s, w], [s, w])] = [[1, -1], [-1, 1]]
    return k, m, [s, w], size - 1, kp * pen, 2 * zeta * np.sqrt(kp * m_red) * pen


def amplification(dt, n_sub, k, m, contact, fixed, kp, cp, hold):
    size = len(m)
    bulk = np.ones(size, bool)
    bulk[contact] = False
    bulk[fixed] = False
    h = dt / n_sub

    def step(x):
        u, v = x[:size].copy(), x[size:].copy()
        a = -(k @ u) / m
        v[bulk] += dt * a[bulk]
        u_new = u.copy()
        u_new[bulk] += dt * v[bulk]
        uc, vc = u.copy(), v.copy()
        for j in range(n_sub):
            f = -(kp @ uc) - cp @ vc
            kick = h * f[contact] / m[contact]
            if hold:
                kick += h * a[contact]
            elif j == 0:
                kick += dt * a[contact]
            vc[contact] += kick
            uc[contact] += h * vc[contact]
        u_new[contact], v[contact] = uc[contact], vc[contact]
        return np.concatenate([u_new, v])

    return np.column_stack([step(e) for e in np.eye(2 * size)])


def main():
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 6
    hold = "hold" in sys.argv[2:]
    grid = np.arange(0.02, 1.0 + 1e-9, 0.004)
    for zeta in (0.0, 0.5):
        for ratio in (0.3, 0.6, 0.8, 0.945, 1.1, 1.3, 1.6, 2.0, 2.5, 3.0):
            k, m, contact, fixed, kp, cp = system(n, ratio, zeta)
            bound = min(0.95, 1.75 / (2 * ratio))
            cells = []
            for n_sub in (2, 3, 4):
                first = next((c for c in grid
                              if max(abs(np.linalg.eigvals(amplification(
                                  c, n_sub, k, m, contact, fixed, kp, cp, hold)))) > 1 + 1e-7),
                             None)
                cells.append(f"N={n_sub}: " + ("-" if first is None else
                                               f"{first:.3f} ({first / bound:.3f})"))
            print(f"zeta {zeta}, omega_p/omega_mesh {ratio}: bound {bound:.3f}; " +
                  ", ".join(cells), flush=True)


main()
