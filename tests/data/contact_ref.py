#!/usr/bin/env python3
"""High-precision reference for G(q1) and A/A0 (eqs. B11, B12) on layered scenes.

G1 = (pi/4) E0*^2 int_{q0}^{q1} q^3 C(q) S(qd)^-2 dq for the paper's self-affine spectrum
(H = 1, q0 = 1e5, q1 = 1e8 1/m, rms slope 1, so C0 = 1 / (2 pi int q^3 (q/q0)^-4 dq)), with
S taken from the 6x6 boundary-value solve in kernels_ref.py (no closed form), integrated with
mpmath's tanh-sinh quadrature in ln q at 30 digits.

Regenerate:  python3 tests/data/contact_ref.py > tests/data/contact_ref.csv
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import kernels_ref  # noqa: E402

kernels_ref.mp.mp.dps = 30
mp.mp.dps = 30

Q0, Q1, H = mp.mpf('1e5'), mp.mpf('1e8'), 1
# xi^2 = 2 pi C0 q0^4 int_{q0}^{q1} q^{-1} dq  (H = 1: q^3 C = C0 q0^4 / q)
C0 = 1 / (2 * mp.pi * Q0 ** 4 * mp.log(Q1 / Q0))


def g1(e0, nu0, e1, nu1, d):
    e0s = e0 / (1 - nu0 ** 2)

    def integrand(u):
        q = mp.exp(u)
        s = kernels_ref.kernels(e0 / e1, nu0, nu1, q * d)[0]
        return q ** 4 * C0 * (q / Q0) ** (-2 * (1 + H)) / s ** 2

    pts = mp.linspace(mp.log(Q0), mp.log(Q1), 13)
    return mp.pi / 4 * e0s ** 2 * mp.quad(integrand, pts)


def main():
    print('e0,nu0,e1,nu1,d,p0,g1,area')
    cases = [
        ('1e6', '0.5', '1e11', '0.5', '1e-5', '1e5'),
        ('1e6', '0.5', '1e11', '0.5', '1e-7', '1e5'),
        ('1e6', '0.49985', '1e11', '0.3', '3e-6', '1e5'),
        ('1e9', '0.3', '1e6', '0.5', '1e-5', '1e4'),
    ]
    for e0, nu0, e1, nu1, d, p0 in cases:
        g = g1(mp.mpf(e0), mp.mpf(nu0), mp.mpf(e1), mp.mpf(nu1), mp.mpf(d))
        a = mp.erf(mp.mpf(p0) / (2 * mp.sqrt(g)))
        print(','.join([e0, nu0, e1, nu1, d, p0, mp.nstr(g, 20), mp.nstr(a, 20)]))


if __name__ == '__main__':
    main()
