#!/usr/bin/env python3
"""High-precision reference for the tangential-load kernels g_t, f_t, h and the coupling c.

Independent of the closed forms in src/layer/tangential.rs: every value here comes from a
direct numerical solution, with mpmath at 50 significant digits, of the boundary-value problem
of one Fourier mode of tangential traction on a film (material 0, 0 <= z <= d) bonded to an
elastic half-space (material 1, z >= d); z points into the solid, tension positive.

In-plane (tangential_ref.csv, columns g_t, f_t, c): the 6x6 system of the Papkovich-Neuber
representation 2 mu u = grad(phi + z psi) - 4(1 - nu) psi e_z (as in kernels_ref.py), with
sigma_xz(x, 0) = cos(qx), sigma_zz(x, 0) = 0, and u_x, u_z, sigma_zz, sigma_xz continuous at
z = d. Then
  sigma_xz(x, d) = g_t cos(qx),   sigma_zz(x, d) = f_t sin(qx),
  u_z(x, 0) = 2 c sin(qx) / (q E0*)  (the normal-tangential coupling, in the units of S).
Antiplane (column h): the 2x2 system for u_y = A e^{-qz} + B e^{q(z-d)} in the film, with
sigma_yz(x, 0) = cos(qx) and the substrate's decaying solution e^{-q(z-d)} eliminated through
its impedance sigma_yz(d) = -G1 q u_y(d); sigma_yz(x, d) = h cos(qx).
Rows: E0/E1 in {1e-8, 1e-4, 1e-2, 1, 1e2, 1e4, 1e8}, nu0, nu1 in {0, 0.3, 0.49, 0.5}, q d from
1e-8 to 1e4 (one point a decade), plus, for every pair whose g_t changes sign, the zero of g_t
(found to 40 digits) and q d at 1 +- 1e-3 and 1 +- 1e-6 times it.

3D single mode (tangential_3d_ref.csv): a different formulation, the state vector
y = (u_x, u_y, u_z, s_xz, s_yz, s_zz) of the mode e^{i(k1 x + k2 y)}, k = q (cos phi, sin phi),
with y' = A y from the 3D Navier equations (coefficients finite at nu = 1/2); the film is
crossed with the matrix exponential, the substrate's decaying solutions are the null space of
(A1 + q)^2. The traction is sigma_xz(x, y, 0) = cos(k.r) along x, at an angle phi to the
wavevector. Columns: the interface sigma_xz, sigma_yz (coefficients of cos(k.r)), sigma_zz
(of sin(k.r)) and u_z(0) in the units of c; the kernels predict g_t cos^2 phi + h sin^2 phi,
(g_t - h) cos phi sin phi, f_t cos phi and c cos phi.

Every value is recomputed at 90 digits and the script stops if the two differ by more than
1e-30 (|value| + e^{-qd}).

Regenerate:  python3 tests/data/tangential_ref.py   (writes both CSV files next to this one)
"""
import os
import mpmath as mp

I = mp.mpc(0, 1)


def columns(nu, mu, s, z, kind):
    """(u_x, u_z, s_zz, s_xz) at depth z of phi (or psi) = e^{s z} e^{ix} (q = 1)."""
    e = mp.exp(s * z)
    if kind == 'phi':
        return [I * e / (2 * mu), s * e / (2 * mu), e, I * s * e]
    return [z * I * e / (2 * mu), (e + z * s * e - 4 * (1 - nu) * e) / (2 * mu),
            z * e - 2 * (1 - nu) * s * e, z * I * s * e - (1 - 2 * nu) * I * e]


def in_plane(e0, nu0, nu1, x):
    """g_t, f_t, c for E1 = 1, q = 1, d = x."""
    mu0 = e0 / (2 * (1 + nu0))
    mu1 = 1 / (2 * (1 + nu1))
    film = [('phi', -1), ('phi', 1), ('psi', -1), ('psi', 1)]
    # Growing film functions as e^{z - x} (scaled by e^{-x}); substrate ones as e^{-(z - x)}.
    def film_cols(z):
        out = []
        for k, s in film:
            c = columns(nu0, mu0, s, z, k)
            if s > 0:
                c = [v * mp.exp(-x) for v in c]
            out.append(c)
        return out
    top = film_cols(mp.mpf(0))
    inter = film_cols(x)
    sub = [columns(nu1, mu1, -1, mp.mpf(0), k) for k in ('phi', 'psi')]
    # The substrate's psi column carries z; at z = d that is z = x, not 0: rebuild it there.
    sub[1] = [v * mp.exp(x) for v in columns(nu1, mu1, -1, x, 'psi')]
    rows = [[c[2] for c in top] + [0, 0], [c[3] for c in top] + [0, 0]]
    for j in range(4):
        rows.append([c[j] for c in inter] + [-sub[0][j], -sub[1][j]])
    coef = mp.lu_solve(mp.matrix(rows), mp.matrix([0, 1, 0, 0, 0, 0]))
    szz = sum(coef[c] * inter[c][2] for c in range(4))
    sxz = sum(coef[c] * inter[c][3] for c in range(4))
    uz0 = sum(coef[c] * top[c][1] for c in range(4))
    e0star = e0 / (1 - nu0 ** 2)
    assert abs(mp.im(sxz)) <= mp.mpf(10) ** (-mp.mp.dps + 15) * (1 + abs(sxz))
    return mp.re(sxz), -mp.im(szz), -mp.im(uz0) * e0star / 2


def antiplane(e0, nu0, nu1, x):
    mu0 = e0 / (2 * (1 + nu0))
    mu1 = 1 / (2 * (1 + nu1))
    # u_y = A e^{-z} + B e^{z - x}; sigma_yz = mu0 (-A e^{-z} + B e^{z - x}).
    m = mp.matrix([[-mu0, mu0 * mp.exp(-x)],
                   [-mu0 * mp.exp(-x) + mu1 * mp.exp(-x), mu0 + mu1]])
    a, b = mp.lu_solve(m, mp.matrix([1, 0]))
    return mu0 * (-a * mp.exp(-x) + b)


def system_matrix(nu, mu, k1, k2):
    c1 = (1 - 2 * nu) / (2 * mu * (1 - nu))
    beta = nu / (1 - nu)
    gamma = 2 * mu * nu / (1 - nu)
    a = mp.zeros(6, 6)
    # rows: u_x', u_y', u_z', s_xz', s_yz', s_zz'; columns: u_x, u_y, u_z, s_xz, s_yz, s_zz
    a[0, 3] = 1 / mu; a[0, 2] = -I * k1
    a[1, 4] = 1 / mu; a[1, 2] = -I * k2
    a[2, 5] = c1; a[2, 0] = -beta * I * k1; a[2, 1] = -beta * I * k2
    # lambda div u = beta s_zz + gamma i (k1 u_x + k2 u_y)
    ld = [gamma * I * k1, gamma * I * k2, 0, 0, 0, beta]
    sxx = [ld[j] + (2 * mu * I * k1 if j == 0 else 0) for j in range(6)]
    syy = [ld[j] + (2 * mu * I * k2 if j == 1 else 0) for j in range(6)]
    sxy = [mu * I * k2, mu * I * k1, 0, 0, 0, 0]
    for j in range(6):
        a[3, j] = -I * k1 * sxx[j] - I * k2 * sxy[j]
        a[4, j] = -I * k1 * sxy[j] - I * k2 * syy[j]
    a[5, 3] = -I * k1; a[5, 4] = -I * k2
    return a


def mode3d(e0, nu0, nu1, x, phi):
    mu0 = e0 / (2 * (1 + nu0))
    mu1 = 1 / (2 * (1 + nu1))
    k1, k2 = mp.cos(phi), mp.sin(phi)
    t = mp.expm(system_matrix(nu0, mu0, k1, k2) * x)
    a1 = system_matrix(nu1, mu1, k1, k2)
    p = (a1 + mp.eye(6)) ** 2
    pt = p * t
    # unknowns u(0); traction at 0 is (1, 0, 0)
    lhs = mp.matrix(6, 3)
    rhs = mp.matrix(6, 1)
    for r in range(6):
        for c in range(3):
            lhs[r, c] = pt[r, c]
        rhs[r] = -pt[r, 3]
    lh = lhs.H
    u0 = mp.lu_solve(lh * lhs, lh * rhs)
    y0 = mp.matrix([u0[0], u0[1], u0[2], 1, 0, 0])
    resid = mp.norm(pt * y0) / mp.norm(pt)
    assert resid < mp.mpf(10) ** (-mp.mp.dps // 2), resid
    yd = t * y0
    e0star = e0 / (1 - nu0 ** 2)
    for v in (yd[3], yd[4]):
        assert abs(mp.im(v)) < mp.mpf(10) ** (-mp.mp.dps // 2)
    return mp.re(yd[3]), mp.re(yd[4]), -mp.im(yd[5]), -mp.im(y0[2]) * e0star / 2


def at_two_precisions(fn, *args):
    with mp.workdps(50):
        lo = fn(*[mp.mpf(a) for a in args])
    with mp.workdps(90):
        hi = fn(*[mp.mpf(a) for a in args])
    lo = lo if isinstance(lo, tuple) else (lo,)
    hi = hi if isinstance(hi, tuple) else (hi,)
    for a, b in zip(lo, hi):
        scale = abs(b) + mp.exp(-mp.mpf(args[3]))
        assert abs(a - b) <= mp.mpf('1e-30') * scale, (fn.__name__, args, a, b)
    return lo


def fmt(v):
    return mp.nstr(v, 19, min_fixed=0, max_fixed=0)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ratios = ['1e-8', '1e-4', '1e-2', '1', '1e2', '1e4', '1e8']
    nus = ['0', '0.3', '0.49', '0.5']
    qds = ['1e%d' % k for k in range(-8, 5)]
    with open(os.path.join(here, 'tangential_ref.csv'), 'w') as out:
        out.write('e0_over_e1,nu0,nu1,qd,g_t,f_t,h,c\n')
        for r in ratios:
            for nu0 in nus:
                for nu1 in nus:
                    pts = [mp.mpf(q) for q in qds]
                    with mp.workdps(50):
                        gs = [in_plane(mp.mpf(r), mp.mpf(nu0), mp.mpf(nu1), q)[0] for q in pts]
                    extra = []
                    for k in range(len(pts) - 1):
                        if gs[k] * gs[k + 1] < 0:
                            with mp.workdps(60):
                                g = lambda q: in_plane(mp.mpf(r), mp.mpf(nu0), mp.mpf(nu1), q)[0]
                                z = mp.findroot(g, (pts[k], pts[k + 1]), solver='anderson')
                            extra += [z * (1 + mp.mpf(s)) for s in ('-1e-3', '-1e-6', '0', '1e-6', '1e-3')]
                    for q in sorted(pts + extra):
                        qs = mp.nstr(q, 40) if q in extra else mp.nstr(q, 17)
                        g, f, c = at_two_precisions(in_plane, r, nu0, nu1, qs)
                        (h,) = at_two_precisions(antiplane, r, nu0, nu1, qs)
                        out.write(','.join([r, nu0, nu1, qs] + [fmt(v) for v in (g, f, h, c)]) + '\n')
    pairs = [('1', '0.3', '0.3'), ('1e-5', '0.5', '0.5'), ('1e-5', '0.49', '0.3'),
             ('1e3', '0', '0.5'), ('1e-2', '0.3', '0'), ('10', '0.5', '0.25')]
    with open(os.path.join(here, 'tangential_3d_ref.csv'), 'w') as out:
        out.write('e0_over_e1,nu0,nu1,qd,phi,sxz,syz,szz,uz\n')
        for r, nu0, nu1 in pairs:
            for qd in ['1e-3', '0.1', '1', '3', '10']:
                for phi in ['0', '0.3', '0.7853981633974483', '1.2', '1.5707963267948966']:
                    vals = at_two_precisions(mode3d, r, nu0, nu1, qd, phi)
                    out.write(','.join([r, nu0, nu1, qd, phi] + [fmt(v) for v in vals]) + '\n')


if __name__ == '__main__':
    main()
