#!/usr/bin/env python3
"""High-precision reference for the interface stresses of a thick film, where they fall below
f64's normal range: sigma_rms and tau_rms at the film-substrate interface (eqs. B8-B10 as in
notes.md) for the paper's scene (examples/paper-rubber-on-steel.toml: rubber E0 = 1 MPa,
nu0 = 0.5, on steel E1 = 1e11 Pa, nu1 = 0.5; p0 = 0.1 MPa; self-affine H = 1, q0 = 1e5,
q1 = 1e8 1/m, rms slope 1) at thicknesses d with q0 d from 100 to 800.

  sigma^2 = 2 int_{q0}^{q1} P(G(q)) f(qd)^2 dG(q),   tau^2 the same with g(qd),
  G(q) = (pi/4) E0*^2 int_{q0}^{q} q'^3 C S^-2 dq',  P = erf(p0 / (2 sqrt G)).

Independent of the engine: f, g from the 6x6 boundary-value solve of kernels_ref.py (no closed
form), and G in closed form. At q d >= 100, S - 1 = O((qd)^2 e^{-2qd}) < 1e-80, so S^-2 = 1 and,
with q^3 C = C0 q0^4 / q and C0 = 1/(2 pi q0^4 ln(q1/q0)) (rms slope 1),
G(x) = K ln(x/x0), K = E0*^2 / (8 ln(q1/q0)), x = q d, x0 = q0 d. Then

  sigma^2 = 2K int_{x0}^{x0+150} erf(p0 / (2 sqrt(K ln(x/x0)))) f(x)^2 dx/x,

taken as e^{-2 x0} times the integral of (f e^{x0})^2 (mpmath's quad judges convergence by an
absolute error, so its integrand is kept of order 1),

cut at x0 + 150 (f^2 falls like e^{-2x}: the rest is below e^{-290} of the whole), by mpmath's
tanh-sinh quadrature at 40 digits on pieces [x0, x0 + 1/8, 1/4, ..., 64, 150] (the integrand
varies on the scale 1/2 near x0), checked against Gauss-Legendre on pieces graded geometrically
towards x0 (x0 + 2^k, k = -60..6: P = erf(c/sqrt(ln(x/x0))) is smooth but not analytic at x0,
and each piece [a, 2a] is analytic in a disc scaled to it); the two agree to 1e-22 relative or
the script stops. d is the f64 value the command line gives
(printed by the engine as thickness_m), taken exactly.

Run: python3 tests/data/interface_far_ref.py   (about a minute; prints the table the test
tests/it/interface_far.rs holds).
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True
import kernels_ref  # noqa: E402  (sets mp.dps = 100 on import)

mp.mp.dps = 40
E0, NU0, E1, NU1 = mp.mpf(10) ** 6, mp.mpf(1) / 2, mp.mpf(10) ** 11, mp.mpf(1) / 2
P0, Q0, Q1 = mp.mpf(10) ** 5, mp.mpf(10) ** 5, mp.mpf(10) ** 8
E0S = E0 / (1 - NU0 ** 2)
K = E0S ** 2 / (8 * mp.log(Q1 / Q0))


def rms(d):
    x0 = Q0 * mp.mpf(d)
    cache = {}

    def fg(x):
        if x not in cache:
            _, f, g = kernels_ref.kernels(E0 / E1, NU0, NU1, x)
            cache[x] = (f, g)
        return cache[x]

    def integrand(x, which):
        if x <= x0:
            p = mp.mpf(1)
        else:
            p = mp.erf(P0 / (2 * mp.sqrt(K * mp.log(x / x0))))
        # times e^{2 x0}: mpmath's quad stops on an absolute error of 10^-dps, so the
        # integrand is kept of order 1 (the factor is taken out again below)
        return p * (fg(x)[which] * mp.exp(x0)) ** 2 / x

    ends = [x0] + [x0 + mp.mpf(2) ** k for k in range(-3, 7)] + [x0 + 150]
    graded = [x0] + [x0 + mp.mpf(2) ** k for k in range(-60, 7)] + [x0 + 150]
    out = []
    for which in (0, 1):
        ts = mp.quad(lambda x: integrand(x, which), ends, method="tanh-sinh")
        gl = mp.quad(lambda x: integrand(x, which), graded, method="gauss-legendre")
        assert abs(ts - gl) <= mp.mpf(10) ** -22 * abs(ts), (d, which, ts, gl)
        out.append(mp.sqrt(2 * K * ts) * mp.exp(-x0))
    return out


def main():
    print("d_m,q0_d,sigma_rms_interface_pa,tau_rms_interface_pa")
    for d in (0.001, 0.003, 0.005, 0.006, 0.007, 0.008):
        s, t = rms(d)
        print(f"{d!r},{mp.nstr(Q0 * mp.mpf(d), 17)},{mp.nstr(s, 20)},{mp.nstr(t, 20)}")


if __name__ == "__main__":
    main()
