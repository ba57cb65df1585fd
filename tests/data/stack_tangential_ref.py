#!/usr/bin/env python3
"""High-precision reference for the tangential-load kernels of a layer stack: at every
interface k, g_t,k, f_t,k (in-plane) and h_k (antiplane) (src/layer/stack.rs).

Independent of the Rust algorithm (a bottom-up stiffness recursion): for each case this solves,
with mpmath, the whole linear boundary-value problem of one Fourier mode of tangential
traction on N perfectly bonded layers (layer k: E_k, nu_k, thickness d_k, top first) on an
elastic half-space, all unknowns at once. z points into the solid; tension is positive.

In-plane: the Papkovich-Neuber representation of stack_ref.py (4 unknowns per layer, 2 in the
half-space; its `columns` is imported from there), with the top conditions
sigma_xz(x, 0) = cos(qx), sigma_zz(x, 0) = 0 in place of the normal load, and u_x, u_z,
sigma_zz, sigma_xz continuous at every interface. Then, at interface k (depth
z_k = d_1 + ... + d_k, below layer k; the conventions of the one-layer g_t, f_t of notes.md,
"Sliding friction"):
  sigma_xz(x, z_k) = g_t,k cos(qx),   sigma_zz(x, z_k) = f_t,k sin(qx).
Antiplane: u_y = A_k e^{-q z'} + B_k e^{q (z' - d_k)} in layer k (z' the depth below its top),
C e^{-q z'} in the half-space, with sigma_yz(x, 0) = cos(qx) and u_y, sigma_yz continuous at
every interface (2N + 1 unknowns); sigma_yz(x, z_k) = h_k cos(qx).

Every case is solved at 120 and at 160 significant digits; the script stops if the two differ
by more than 1e-40 relative in any output.

The cases: one layer (against the film's closed forms as well), the 3-layer stacks of
stack_ref.py at neighbour modulus ratios 1e8 and 1e-8 both ways, a 3-layer incompressible stack
with ratios 1e8 between every neighbour, a homogeneous 3-layer stack, and the 10-layer ladder
of stack_ref.py; q z_N from 1e-8 to 1e4 (two points a decade), plus, for every interface whose
g_t,k changes sign, q at that zero (rounded to the nearest double) and at 1 +- 1e-6 times it.

CSV row: N, then E_k, nu_k, d_k for k = 1..N, then E_s, nu_s, q, then g_t,k, f_t,k, h_k for
k = 1..N (row length 1 + 3N + 3 + 3N = 4 + 6N). Moduli in Pa, lengths in m, q in 1/m.

Regenerate:  python3 tests/data/stack_tangential_ref.py > tests/data/stack_tangential_ref.csv
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from stack_ref import columns  # noqa: E402


def in_plane(layers, sub, q):
    """layers: [(E, nu, d)], sub: (E, nu); all mpf. Returns [(g_t,k, f_t,k)]."""
    n = len(layers)
    m = 4 * n + 2
    rows = []
    rhs = []

    def layer_cols(k, z):
        e, nu, d = layers[k]
        mu = e / (2 * (1 + nu))
        return [columns(nu, mu, s, q, z, kind, z0)
                for kind, s, z0 in (('phi', -1, 0), ('phi', 1, d), ('psi', -1, 0), ('psi', 1, d))]

    def sub_cols():
        e, nu = sub
        mu = e / (2 * (1 + nu))
        return [columns(nu, mu, -1, q, mp.mpf(0), kind, 0) for kind in ('phi', 'psi')]

    top = layer_cols(0, mp.mpf(0))
    # sigma_zz(0) = 0, sigma_xz(0) = 1 (the coefficient of e^{iqx}: cos(qx) in real terms)
    for j, b in ((2, 0), (3, 1)):
        row = [mp.mpf(0)] * m
        for c in range(4):
            row[c] = top[c][j]
        rows.append(row)
        rhs.append(b)
    for k in range(n):
        above = layer_cols(k, layers[k][2])
        below = layer_cols(k + 1, mp.mpf(0)) if k + 1 < n else sub_cols()
        for j in range(4):
            row = [mp.mpf(0)] * m
            for c in range(4):
                row[4 * k + c] = above[c][j]
            for c, col in enumerate(below):
                row[4 * (k + 1) + c] = -col[j]
            rows.append(row)
            rhs.append(0)
    x = mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))
    out = []
    for k in range(n):
        cols = layer_cols(k, layers[k][2])
        szz = sum(x[4 * k + c] * cols[c][2] for c in range(4))
        sxz = sum(x[4 * k + c] * cols[c][3] for c in range(4))
        # Re[T e^{iqx}] = Re T cos(qx) - Im T sin(qx)
        out.append((mp.re(sxz), -mp.im(szz)))
    return out


def antiplane(layers, sub, q):
    """The h_k of u_y under sigma_yz(x, 0) = cos(qx)."""
    n = len(layers)
    m = 2 * n + 1
    rows = []
    rhs = []
    mus = [e / (2 * (1 + nu)) for e, nu, _ in layers]
    mu_s = sub[0] / (2 * (1 + sub[1]))

    def row_of(entries):
        row = [mp.mpf(0)] * m
        for c, v in entries:
            row[c] = v
        return row

    # sigma_yz(0) = mu_1 q (-A_1 + B_1 e^{-q d_1}) = 1
    e1 = mp.exp(-q * layers[0][2])
    rows.append(row_of([(0, -mus[0] * q), (1, mus[0] * q * e1)]))
    rhs.append(1)
    for k in range(n):
        ek = mp.exp(-q * layers[k][2])
        # layer k at its bottom: u = A e^{-qd} + B, tau = mu q (-A e^{-qd} + B)
        if k + 1 < n:
            ekn = mp.exp(-q * layers[k + 1][2])
            # next layer at its top: u = A' + B' e^{-qd'}, tau = mu' q (-A' + B' e^{-qd'})
            below_u = [(2 * k + 2, -1), (2 * k + 3, -ekn)]
            below_t = [(2 * k + 2, mus[k + 1] * q), (2 * k + 3, -mus[k + 1] * q * ekn)]
        else:
            below_u = [(2 * n, -1)]
            below_t = [(2 * n, mu_s * q)]
        rows.append(row_of([(2 * k, ek), (2 * k + 1, 1)] + below_u))
        rhs.append(0)
        rows.append(row_of([(2 * k, -mus[k] * q * ek), (2 * k + 1, mus[k] * q)] + below_t))
        rhs.append(0)
    x = mp.lu_solve(mp.matrix(rows), mp.matrix(rhs))
    return [mus[k] * q * (-x[2 * k] * mp.exp(-q * layers[k][2]) + x[2 * k + 1]) for k in range(n)]


def solve(layers, sub, q):
    return [(g, f, h) for (g, f), h in zip(in_plane(layers, sub, q), antiplane(layers, sub, q))]


def stacks():
    """(name, layers as (E, nu, d) strings, substrate): total thickness 1 m."""
    return [
        ('1 rubber/steel', [('1e6', '0.5', '1')], ('1e11', '0.5')),
        ('1 hard on soft', [('1e8', '0.3', '1')], ('1', '0.5')),
        ('3 1e8 1e-8', [('1', '0.5', '0.2'), ('1e8', '0.3', '0.3'), ('1', '0.5', '0.5')], ('1e8', '0.5')),
        ('3 1e-8 1e8', [('1e8', '0.2', '0.5'), ('1', '0.5', '0.2'), ('1e8', '0.5', '0.3')], ('1', '0.5')),
        ('3 incompressible 1e8 steps', [('1e-8', '0.5', '0.001'), ('1', '0.5', '0.1'),
                                        ('1e8', '0.5', '0.899')], ('1e16', '0.5')),
        ('3 ptfe/rubber/epoxy', [('5e8', '0.46', '0.05'), ('1e6', '0.5', '0.9'), ('3e9', '0.35', '0.05')],
         ('2e11', '0.3')),
        ('3 homogeneous', [('7', '0.3', '0.25'), ('7', '0.3', '0.35'), ('7', '0.3', '0.4')], ('7', '0.3')),
        ('10 ladder', [(('1e8' if k % 2 else '1'), ('0.5', '0.3', '0', '0.45', '0.49985')[k % 5],
                        '%.2f' % (0.05 + 0.01 * k)) for k in range(10)], ('1e-8', '0.5')),
    ]


def qs():
    out = []
    for e in range(-8, 4):
        out += ['1e%d' % e, '3.1622776601683794e%d' % e]
    out.append('1e4')
    return out


def at(layers, sub, q, dps):
    mp.mp.dps = dps
    lay = [tuple(mp.mpf(v) for v in l) for l in layers]
    s = tuple(mp.mpf(v) for v in sub)
    return solve(lay, s, mp.mpf(q))


def checked(name, layers, sub, q):
    """The outputs at 160 digits, checked against 120."""
    a, b = at(layers, sub, q, 120), at(layers, sub, q, 160)
    for ra, rb in zip(a, b):
        for va, vb in zip(ra, rb):
            if abs(va - vb) > mp.mpf('1e-40') * abs(vb):
                raise SystemExit('%s q=%s: 120 and 160 digits disagree' % (name, q))
    return b


def zeros(name, layers, sub, grid):
    """q (as strings) at the zeros of every g_t,k that changes sign between grid points, and at
    1 +- 1e-6 times them."""
    out = []
    mp.mp.dps = 60
    lay = [tuple(mp.mpf(v) for v in l) for l in layers]
    s = tuple(mp.mpf(v) for v in sub)
    vals = [(mp.mpf(q), in_plane(lay, s, mp.mpf(q))) for q in grid]
    for k in range(len(layers)):
        for (qa, ra), (qb, rb) in zip(vals, vals[1:]):
            if ra[k][0] * rb[k][0] < 0:
                g = lambda lnq: in_plane(lay, s, mp.exp(lnq))[k][0]
                z = mp.exp(mp.findroot(g, (mp.log(qa), mp.log(qb)), solver='anderson', tol=1e-50))
                for f in ('1', '1.000001', '0.999999'):
                    out.append(repr(float(z * mp.mpf(f))))
    return out


def main():
    print('# N,E_k,nu_k,d_k (k=1..N),E_s,nu_s,q,g_t_k,f_t_k,h_k (k=1..N)')
    for name, layers, sub in stacks():
        grid = qs()
        for q in grid + zeros(name, layers, sub, grid):
            vals = checked(name, layers, sub, q)
            fields = [str(len(layers))] + [v for l in layers for v in l] + list(sub) + [q]
            fields += [mp.nstr(v, 20) for r in vals for v in r]
            print(','.join(fields))


if __name__ == '__main__':
    main()
