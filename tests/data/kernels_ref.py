#!/usr/bin/env python3
"""High-precision reference for the layer kernels S(qd), f(qd), g(qd).

Independent of the closed forms in src/layer.rs: for each case this solves, with mpmath at
100 significant digits, the 6x6 linear boundary-value problem of one Fourier mode of normal
load on a film (material 0, 0 <= z <= d) bonded to a half-space (material 1, z >= d), using the
Papkovich-Neuber representation 2 mu u = grad(phi + z psi) - 4(1 - nu) psi e_z with harmonic
phi, psi (finite at nu = 1/2). Boundary conditions: sigma_zz(0) = s0, sigma_xz(0) = 0
(frictionless top), continuity of u_x, u_z, sigma_zz, sigma_xz at z = d (bonded).
z points into the solid; tension is positive, so a pressure p is sigma_zz = -p.

Outputs (definitions used by the code):
  S = u_z(0) q E0* / (2 p)                (eq. 6-7: the surface compliance over the film's half-space one)
  f = sigma_zz(d) / sigma_zz(0)
  g defined by sigma_xz(x, d) = g s0 sin(qx) when sigma_zz(x, 0) = s0 cos(qx)

Regenerate:  python3 tests/data/kernels_ref.py > tests/data/kernels_ref.csv
"""
import mpmath as mp

mp.mp.dps = 100


def columns(nu, mu, s, q, z, kind):
    """(u_x, u_z, s_zz, s_xz) at depth z for phi (kind 'phi') or psi ('psi') = e^{s q z},
    with the common factor e^{iqx} removed (d/dx -> i q)."""
    e = mp.exp(s * q * z)
    i = mp.mpc(0, 1)
    if kind == 'phi':
        ux = i * q * e / (2 * mu)
        uz = s * q * e / (2 * mu)
        szz = q * q * e
        sxz = i * s * q * q * e
    else:
        ux = z * i * q * e / (2 * mu)
        uz = (e + z * s * q * e - 4 * (1 - nu) * e) / (2 * mu)
        szz = z * q * q * e - 2 * (1 - nu) * s * q * e
        sxz = z * i * s * q * q * e - (1 - 2 * nu) * i * q * e
    return [ux, uz, szz, sxz]


def kernels(e_ratio, nu0, nu1, qd):
    e1 = mp.mpf(1)
    e0 = mp.mpf(e_ratio)
    nu0 = mp.mpf(nu0)
    nu1 = mp.mpf(nu1)
    mu0 = e0 / (2 * (1 + nu0))
    mu1 = e1 / (2 * (1 + nu1))
    q = mp.mpf(1)
    d = mp.mpf(qd)
    film = [('phi', -1), ('phi', 1), ('psi', -1), ('psi', 1)]
    rows = []
    rhs = []
    # top: s_zz = 1, s_xz = 0
    top = [columns(nu0, mu0, s, q, mp.mpf(0), k) for k, s in film]
    rows.append([c[2] for c in top] + [0, 0]); rhs.append(1)
    rows.append([c[3] for c in top] + [0, 0]); rhs.append(0)
    # interface: film - substrate = 0 for u_x, u_z, s_zz, s_xz.
    # Substrate functions e^{-q(z-d)} evaluated at z = d: build them with the shift.
    inter = [columns(nu0, mu0, s, q, d, k) for k, s in film]
    sub = []
    for k in ('phi', 'psi'):
        c = columns(nu1, mu1, -1, q, d, k)
        shift = mp.exp(q * d)  # e^{-q(z-d)} = e^{-qz} e^{qd}
        sub.append([v * shift for v in c])
    for j in range(4):
        rows.append([c[j] for c in inter] + [-sub[0][j], -sub[1][j]]); rhs.append(0)
    # Scale the growing film columns (e^{+qz}) by e^{-qd} to keep the matrix well scaled.
    scale = [1, mp.exp(-q * d), 1, mp.exp(-q * d), 1, 1]
    m = mp.matrix([[rows[r][c] * scale[c] for c in range(6)] for r in range(6)])
    x = mp.lu_solve(m, mp.matrix(rhs))
    coef = [x[c] * scale[c] for c in range(6)]
    uz0 = sum(coef[c] * top[c][1] for c in range(4))
    szzd = sum(coef[c] * inter[c][2] for c in range(4))
    sxzd = sum(coef[c] * inter[c][3] for c in range(4))
    e0star = e0 / (1 - nu0 ** 2)
    p = -1  # s0 = 1 is a tension; the compliance ratio is sign-free
    s_val = mp.re(uz0) * q * e0star / (2 * p)
    f_val = mp.re(szzd)
    # Re[T e^{iqx}] = Re T cos - Im T sin  =>  g = -Im T
    g_val = -mp.im(sxzd)
    return s_val, f_val, g_val


def main():
    qds = [mp.mpf(10) ** (k / mp.mpf(2)) for k in range(-16, 9)]  # 1e-8 .. 1e4
    ratios = ['1e-8', '1e-5', '1e-3', '0.1', '1', '10', '1e3', '1e5', '1e8']
    nus = [('0.5', '0.5'), ('0.5', '0.3'), ('0.49985', '0.5'), ('0', '0.5'), ('0.25', '0.25'), ('0', '0')]
    print('e0_over_e1,nu0,nu1,qd,S,f,g')
    for r in ratios:
        for nu0, nu1 in nus:
            for qd in qds:
                s, f, g = kernels(mp.mpf(r), mp.mpf(nu0), mp.mpf(nu1), qd)
                print(','.join([r, nu0, nu1, mp.nstr(qd, 17)] + [mp.nstr(v, 20) for v in (s, f, g)]))


if __name__ == '__main__':
    main()
