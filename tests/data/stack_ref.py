#!/usr/bin/env python3
"""High-precision reference for the layer-stack kernels S, f_k, g_k (src/layer/stack.rs).

Independent of the Rust algorithm (a bottom-up stiffness recursion on a first-order system):
for each case this solves, with mpmath, the full linear boundary-value problem of one Fourier
mode of normal load on N perfectly bonded layers (layer k: E_k, nu_k, thickness d_k, top first)
on an elastic half-space, all unknowns at once. Each layer carries the Papkovich-Neuber
representation 2 mu u = grad(phi + z' psi) - 4(1 - nu) psi e_z (finite at nu = 1/2) with
phi, psi in {e^{-q z'}, e^{q (z' - d_k)}}, z' the depth below the layer's top (4 unknowns per
layer; every basis function is at most 1 inside its layer); the half-space has the two decaying
ones (2 unknowns). Equations: sigma_zz(0) = s0, sigma_xz(0) = 0 (frictionless top), continuity
of u_x, u_z, sigma_zz, sigma_xz at every interface (bonded). z points into the solid; tension
is positive, so a pressure p is sigma_zz = -p.

Outputs (the definitions the code uses, notes.md "Layer stacks"):
  S = u_z(0) q E1* / (2 p)        compliance over that of a half-space of the TOP layer's material
  f_k = sigma_zz(z_k) / sigma_zz(0) at interface k (depth z_k = d_1 + ... + d_k, below layer k)
  g_k by sigma_xz(x, z_k) = g_k s0 sin(qx) when sigma_zz(x, 0) = s0 cos(qx)

Every case is solved at 120 and at 160 significant digits; the script stops if the two differ
by more than 1e-40 relative in any output (the matrix is badly scaled at extreme contrasts, so
this is the check that the printed 20 digits are right).

CSV row: N, then E_k, nu_k, d_k for k = 1..N, then E_s, nu_s, q, S, then f_k, g_k for k = 1..N
(row length 3N + 5 + 2N). Moduli in Pa, lengths in m, q in 1/m.

Regenerate:  python3 tests/data/stack_ref.py > tests/data/stack_ref.csv
"""
import mpmath as mp


def columns(nu, mu, s, q, z, kind, z0):
    """(u_x, u_z, s_zz, s_xz) at local depth z for phi (kind 'phi') or psi ('psi') =
    e^{s q (z - z0)}, the common factor e^{iqx} removed (d/dx -> i q)."""
    e = mp.exp(s * q * (z - z0))
    i = mp.mpc(0, 1)
    if kind == 'phi':
        return [i * q * e / (2 * mu), s * q * e / (2 * mu), q * q * e, i * s * q * q * e]
    ux = z * i * q * e / (2 * mu)
    uz = (e + z * s * q * e - 4 * (1 - nu) * e) / (2 * mu)
    szz = z * q * q * e - 2 * (1 - nu) * s * q * e
    sxz = z * i * s * q * q * e - (1 - 2 * nu) * i * q * e
    return [ux, uz, szz, sxz]


def solve(layers, sub, q):
    """layers: [(E, nu, d)], sub: (E, nu); all mpf. Returns S, [(f_k, g_k)]."""
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
    for j, b in ((2, 1), (3, 0)):
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
    uz0 = sum(x[c] * top[c][1] for c in range(4))
    e1, nu1, _ = layers[0]
    s_val = mp.re(uz0) * q * (e1 / (1 - nu1 ** 2)) / (2 * -1)
    out = []
    for k in range(n):
        cols = layer_cols(k, layers[k][2])
        szz = sum(x[4 * k + c] * cols[c][2] for c in range(4))
        sxz = sum(x[4 * k + c] * cols[c][3] for c in range(4))
        # Re[T e^{iqx}] = Re T cos - Im T sin  =>  g = -Im T
        out.append((mp.re(szz), -mp.im(sxz)))
    return s_val, out


def stacks():
    """(name, layers as (E, nu, d) strings, substrate, q values)."""
    # q z from 1e-8 to 1e4 (3 per decade) against the total thickness 1 m
    qs = []
    for e in range(-8, 4):
        qs += ['1e%d' % e, '3.1622776601683794e%d' % e]
    qs.append('1e4')
    few = ['1e-8', '1e-5', '1e-3', '0.1', '1', '3', '10', '100', '1e4']
    return [
        # N = 1: the bilayer
        ('1 rubber/steel', [('1e6', '0.5', '1')], ('1e11', '0.5'), qs),
        ('1 hard on soft', [('1e8', '0.3', '1')], ('1', '0.5'), qs),
        # N = 2
        ('2 rubber/epoxy/steel', [('1e6', '0.5', '0.5'), ('3e9', '0.35', '0.5')], ('2e11', '0.3'), qs),
        ('2 soft/stiff 1e8 up', [('1', '0.5', '0.3'), ('1e8', '0.5', '0.7')], ('1', '0.5'), qs),
        ('2 stiff/soft 1e-8', [('1e8', '0.25', '0.6'), ('1', '0.5', '0.4')], ('1e8', '0'), qs),
        ('2 nu 0 and 0.5', [('2', '0', '0.2'), ('1', '0.5', '0.8')], ('3', '0.49985'), qs),
        ('2 thin primer', [('1e6', '0.5', '1'), ('3e9', '0.35', '1e-6')], ('2e11', '0.3'), qs),
        ('2 homogeneous', [('1', '0.3', '0.4'), ('1', '0.3', '0.6')], ('1', '0.3'), few),
        # N = 3 at extreme contrasts both ways
        ('3 1e8 1e-8', [('1', '0.5', '0.2'), ('1e8', '0.3', '0.3'), ('1', '0.5', '0.5')], ('1e8', '0.5'), qs),
        ('3 1e-8 1e8', [('1e8', '0.2', '0.5'), ('1', '0.5', '0.2'), ('1e8', '0.5', '0.3')], ('1', '0.5'), qs),
        ('3 ptfe/rubber/epoxy', [('5e8', '0.46', '0.05'), ('1e6', '0.5', '0.9'), ('3e9', '0.35', '0.05')],
         ('2e11', '0.3'), qs),
        ('3 graded', [('1e-8', '0.5', '0.001'), ('1', '0.5', '0.1'), ('1e8', '0.5', '0.899')], ('1e16', '0.5'), qs),
        # N = 4
        ('4 alternating', [('1', '0.5', '0.25'), ('1e8', '0.4', '0.25'), ('1', '0.5', '0.25'),
                           ('1e8', '0.5', '0.25')], ('1', '0.5'), qs),
        ('4 mixed', [('3e9', '0.35', '1e-4'), ('1e6', '0.5', '0.5'), ('1e7', '0', '0.3'),
                     ('1e5', '0.45', '0.1999')], ('7e10', '0.33'), qs),
        ('4 incompressible', [('1e6', '0.5', '0.1'), ('1e-2', '0.5', '0.2'), ('1e6', '0.5', '0.3'),
                              ('1e14', '0.5', '0.4')], ('1e6', '0.5'), qs),
        # N = 10
        ('10 ladder', [(('1e8' if k % 2 else '1'), ('0.5', '0.3', '0', '0.45', '0.49985')[k % 5],
                        '%.2f' % (0.05 + 0.01 * k)) for k in range(10)], ('1e-8', '0.5'), qs),
    ]


def main():
    print('# N,E_k,nu_k,d_k (k=1..N),E_s,nu_s,q,S,f_k,g_k (k=1..N)')
    for name, layers, sub, qs in stacks():
        lay = [tuple(mp.mpf(v) for v in l) for l in layers]
        s = tuple(mp.mpf(v) for v in sub)
        for qs_ in qs:
            q = mp.mpf(qs_)
            res = []
            for dps in (120, 160):
                mp.mp.dps = dps
                lay_ = [tuple(mp.mpf(v) for v in l) for l in layers]
                s_ = tuple(mp.mpf(v) for v in sub)
                res.append(solve(lay_, s_, mp.mpf(qs_)))
            (sa, fa), (sb, fb) = res
            vals_a = [sa] + [v for p in fa for v in p]
            vals_b = [sb] + [v for p in fb for v in p]
            for a, b in zip(vals_a, vals_b):
                if abs(a - b) > mp.mpf('1e-40') * abs(b):
                    raise SystemExit('%s q=%s: 120 and 160 digits disagree' % (name, qs_))
            fields = [str(len(layers))] + [v for l in layers for v in l] + list(sub) + [qs_]
            fields += [mp.nstr(v, 20) for v in vals_b]
            print(','.join(fields))


if __name__ == '__main__':
    main()
