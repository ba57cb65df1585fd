#!/usr/bin/env python3
"""High-precision reference for Persson's integrals on layer stacks (src/contact/stack.rs):
G(q1), A/A0, sigma_rms at the top, and sigma_rms, tau_rms at every interface k,
  G(q) = (pi/4) E1*^2 int_{q0}^{q} q'^3 C S^-2 dq'   (E1* the TOP layer's),  P = erf(p0/(2 sqrt G)),
  sigma_k^2 = 2 int P f_k^2 dG,  tau_k^2 = 2 int P g_k^2 dG,  sigma_top^2 = 2 int P dG,
with S, f_k, g_k from stack_ref.py's solve of the whole boundary-value problem (all layers'
Papkovich-Neuber coefficients at once; nothing of the Rust recursion), on the paper's spectrum
(self-affine H = 1, q0 = 1e5, q1 = 1e8 1/m, rms slope 1; C0 rounded to the double that
Spectrum::scaled_to_rms_slope gives, as in interface_ref.py).

Quadrature as interface_ref.py's strategy A (its Panel class): G'(u), f_k e^{q z_k} and
g_k e^{q z_k} on Chebyshev-Lobatto panels in u = ln q; G the exact integral of the interpolant;
2 int P F^2 G' du by Gauss-Legendre on every panel, the first split geometrically towards q0
while G > p0^2/1000. Run twice, (panel width 0.25, 33 nodes, 24-point Gauss, 30 digits) and
(0.2, 41, 30-point, 40 digits): the script stops unless the two agree to 1e-20 relative in every
output and the closed form of sigma_top (2 int P dG in G1) matches to 1e-20.

CSV row: case name, N, then E_k;nu_k;d_k per layer ('|'-separated), E_s, nu_s, p0, g1, area,
sigma_top, then sigma_k, tau_k for k = 1..N ('|'-separated), each to 20 digits.

Regenerate (about a minute):  python3 tests/data/stack_contact_ref.py > tests/data/stack_contact_ref.csv
"""
import os
import sys

import mpmath as mp

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True
import interface_ref  # noqa: E402  (its Panel, gauss, prob, top_closed, paper_c0)
import stack_ref  # noqa: E402

Q0, Q1 = 1e5, 1e8

CASES = [
    # name, layers (E, nu, d), substrate (E, nu), p0
    ('rubber/epoxy/steel', [('1e6', '0.5', '1e-5'), ('3e9', '0.35', '1e-5')], ('2e11', '0.3'), '1e5'),
    ('ptfe/rubber/steel', [('5e8', '0.46', '5e-6'), ('2e6', '0.4998', '1e-4')], ('2e11', '0.29'), '1e5'),
    ('3 extreme', [('1e6', '0.5', '3e-6'), ('1e14', '0.5', '1e-6'), ('1e6', '0.5', '3e-6')],
     ('1e14', '0.5'), '1e5'),
]


def run(case, c0, h, n, m, dps):
    mp.mp.dps = dps
    interface_ref.GL.clear()
    interface_ref.gl_nodes(m)
    _, spec, sub, p0 = case
    layers = [tuple(mp.mpf(v) for v in l) for l in spec]
    sub = tuple(mp.mpf(v) for v in sub)
    p0 = mp.mpf(p0)
    depths = []
    z = mp.mpf(0)
    for l in layers:
        z += l[2]
        depths.append(z)
    e1, nu1 = layers[0][0], layers[0][1]
    pref = mp.pi / 4 * (e1 / (1 - nu1 ** 2)) ** 2
    c0 = mp.mpf(c0)
    qa, qb = mp.log(mp.mpf(Q0)), mp.log(mp.mpf(Q1))

    def fn(u):
        q = mp.exp(u)
        s, fg = stack_ref.solve(layers, sub, q)
        w = c0 * mp.mpf(Q0) ** 4  # q^4 C = C0 q0^4 for H = 1
        out = [pref * w / s ** 2]
        for (f, g), zk in zip(fg, depths):
            grow = mp.exp(q * zk)
            out += [f * grow, g * grow]
        return tuple(out)

    k = int(mp.ceil((qb - qa) / h))
    panels, g_start = [], []
    g = mp.mpf(0)
    for j in range(k):
        p = interface_ref.Panel(qa + (qb - qa) * j / k, qa + (qb - qa) * (j + 1) / k, n, fn)
        panels.append(p)
        g_start.append(g)
        g += p.integral
    g1 = g
    tail = max(p.tail(c) for p in panels for c in range(1 + 2 * len(layers)))

    def values(i, u):
        p = panels[i]
        x = p.x(u)
        gv = g_start[i] + p.g_partial(x)
        pw = interface_ref.prob(p0, gv) * p.at(0, x)
        q = mp.exp(u)
        out = [pw]
        for kk, zk in enumerate(depths):
            decay = mp.exp(-2 * q * zk)
            out += [pw * p.at(1 + 2 * kk, x) ** 2 * decay, pw * p.at(2 + 2 * kk, x) ** 2 * decay]
        return out

    tot = [mp.mpf(0)] * (1 + 2 * len(layers))
    for i, p in enumerate(panels):
        pieces = [(p.a, p.b)]
        if i == 0:
            s = p.b - p.a
            cuts = [p.b]
            while g_start[0] + p.g_partial(p.x(p.a + s)) > p0 ** 2 / 1000 and len(cuts) < 400:
                s /= 2
                cuts.append(p.a + s)
            cuts.append(p.a)
            pieces = list(zip(cuts[1:], cuts[:-1]))
        for a, b in pieces:
            tot = [t + v for t, v in zip(tot, interface_ref.gauss(a, b, m, lambda u: values(i, u)))]
    rms = [mp.sqrt(2 * t) for t in tot]
    top_check = abs(rms[0] ** 2 / interface_ref.top_closed(p0, g1) - 1)
    return [g1, interface_ref.prob(p0, g1)] + rms, tail, top_check


def main():
    c0 = interface_ref.paper_c0()
    print('case,n,layers,e_s,nu_s,p0,g1,area,sigma_top,interfaces')
    for case in CASES:
        a, tail_a, top_a = run(case, c0, mp.mpf('0.25'), 33, 24, 30)
        b, tail_b, top_b = run(case, c0, mp.mpf('0.2'), 41, 30, 40)
        diff = max(abs(x / y - 1) for x, y in zip(a, b) if y != 0)
        print(case[0], 'A-B', mp.nstr(diff, 3), 'tails', mp.nstr(max(tail_a, tail_b), 3),
              'top', mp.nstr(max(top_a, top_b), 3), file=sys.stderr)
        assert diff < 1e-20 and top_a < 1e-20 and top_b < 1e-20, (case[0], diff, top_a, top_b)
        name, spec, sub, p0 = case
        layers = '|'.join(';'.join(l) for l in spec)
        inter = '|'.join(mp.nstr(v, 20) for v in b[3:])
        print(','.join([name, str(len(spec)), layers, sub[0], sub[1], p0]
                       + [mp.nstr(v, 20) for v in b[:3]] + [inter]))


if __name__ == '__main__':
    main()
