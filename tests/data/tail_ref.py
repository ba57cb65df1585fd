#!/usr/bin/env python3
"""High-precision reference for the tail of |tau|, tau = (m + X, Y), X ~ N(0, sx^2),
Y ~ N(0, sy^2) independent (src/tail.rs).

Independent of the polar form in src/tail.rs: P(|tau| > R) is written as the folded-normal
part plus a line integral across the disc,
  P = P(|m + X| > R) + int_{-R}^{R} phi_sx(s - m) erfc(sqrt(R^2 - s^2) / (sqrt(2) sy)) ds,
(the y-tail at each x inside the disc), with s = R cos(theta) to remove the square-root ends,
integrated by mpmath's tanh-sinh quadrature at 30 digits with breakpoints around the
integrand's peak, the integrand scaled to O(1) (mpmath's tolerance is absolute). The level tau* with P = eps is found by mpmath.findroot on ln P.
The script stops unless ln P(tau*) = ln eps to 1e-22 relative and ln P at the level agrees
with a 45-digit recomputation to 1e-22 relative.

Columns: m, sx, sy, eps, tau_star, then a level R = 0.9 tau* and ln P(|tau| > R).

Regenerate:  python3 tests/data/tail_ref.py > tests/data/tail_ref.csv
(or in parts, `tail_ref.py k n` for k = 0..n-1, concatenated in the order of the cases).
"""
import sys

import mpmath as mp


def ln_p(m, sx, sy, r):
    sq2 = mp.sqrt(2)
    folded = (mp.erfc((r - m) / (sq2 * sx)) + mp.erfc((r + m) / (sq2 * sx))) / 2
    def f(th):
        s = r * mp.cos(th)
        return (mp.exp(-(s - m) ** 2 / (2 * sx ** 2)) / (mp.sqrt(2 * mp.pi) * sx)
                * mp.erfc(r * mp.sin(th) / (sq2 * sy)) * r * mp.sin(th))
    # breakpoints: where (R cos th - m)^2/sx^2 + R^2 sin^2 th / sy^2 is least, and widths around
    a = r * r * (1 / sx ** 2 - 1 / sy ** 2)
    b = r * m / sx ** 2
    th0 = mp.acos(b / a) if a > b else mp.mpf(0)
    qtt = 2 * a * mp.sin(th0) ** 2 if a > b else 2 * (b - a)
    w = mp.sqrt(2 / qtt) if qtt > 0 else mp.pi
    pts = set([mp.mpf(0), mp.pi, th0])
    for k in range(-2, 8):
        for t in (th0 - w * 2 ** k, th0 + w * 2 ** k):
            if 0 < t < mp.pi:
                pts.add(t)
    # the y-tail's own scale near theta = 0 and pi
    for k in range(0, 8, 2):
        t = sy / r * 2 ** k
        for u in (t, mp.pi - t):
            if 0 < u < mp.pi:
                pts.add(u)
    pts = sorted(pts)
    # mpmath's quad stops at an absolute error of 10^-dps: scale the integrand to O(1) by the
    # Gaussian factor at the point of the circle nearest the mean (in the metric of X, Y).
    qmin = (r * mp.cos(th0) - m) ** 2 / sx ** 2 + (r * mp.sin(th0)) ** 2 / sy ** 2
    scale = mp.exp(qmin / 2)
    disc = mp.quad(lambda th: f(th) * scale, pts) / scale
    return mp.log(folded + disc)


def quantile(m, sx, sy, eps):
    target = mp.log(eps)
    smax = max(sx, sy)
    lo, hi = m, m + smax * mp.sqrt(-2 * target)
    g = lambda r: ln_p(m, sx, sy, r) - target
    # a few bisections, then the secant method
    for _ in range(3):
        mid = (lo + hi) / 2
        if g(mid) > 0:
            lo = mid
        else:
            hi = mid
    return mp.findroot(g, (lo, hi), solver='anderson')


def row(m, sx, sy, eps):
    m, sx, sy, eps = (mp.mpf(v) for v in (m, sx, sy, eps))
    t = quantile(m, sx, sy, eps)
    lev = t * mp.mpf('0.9')
    return t, lev, ln_p(m, sx, sy, lev)


def main():
    cases = [('0', '1', '0.5'), ('0', '0.2', '1'), ('1', '1', '1'),
             ('3', '1', '0.3'), ('10', '1', '1'), ('2', '0.5', '1'), ('0.5', '1', '0.001'),
             ('5', '0.01', '1')]
    epss = ['0.1', '1e-6', '1e-200', '1e-300']
    # optional "k n": only every n-th case from the k-th (to run parts in parallel)
    if len(sys.argv) == 3:
        k, n = int(sys.argv[1]), int(sys.argv[2])
        cases = cases[k::n]
    if len(sys.argv) != 3 or sys.argv[1] == '0':
        print('m,sx,sy,eps,tau_star,level,ln_p_level')
    for m, sx, sy in cases:
        for eps in epss:
            with mp.workdps(30):
                t, lev, lp = row(m, sx, sy, eps)
                assert abs(ln_p(*(mp.mpf(v) for v in (m, sx, sy)), t) - mp.log(mp.mpf(eps))) \
                    <= mp.mpf('1e-22') * abs(mp.log(mp.mpf(eps)))
            with mp.workdps(45):
                hi = ln_p(*(mp.mpf(v) for v in (m, sx, sy)), lev)
            assert abs(lp - hi) <= mp.mpf('1e-22') * abs(hi), (m, sx, sy, eps, lp, hi)
            print(','.join([m, sx, sy, eps] + [mp.nstr(v, 20) for v in (t, lev, lp)]), flush=True)


if __name__ == '__main__':
    main()
