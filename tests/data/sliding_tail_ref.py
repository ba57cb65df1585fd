#!/usr/bin/env python3
"""High-precision peak |tau| at exceedance eps = 1e-6 for the paper's scene (rubber 1 MPa on
steel 1e11 Pa, both nu = 0.5; self-affine H = 1, q0 = 1e5, q1 = 1e8 1/m, rms slope 1;
p0 = 0.1 MPa; d = 10 um) under sliding with mu = 0, 0.5 and 1 (tests/it/sliding.rs).

The inputs m = mu p0, sx, sy are the shear vector's mean and rms as coatcheck computes them
(f64 values printed by `coatcheck check examples/paper-rubber-on-steel.toml --friction MU
--shear-tail vector --format json`, keys mean_interface_shear_pa, tau_x_rms_interface_pa,
tau_y_rms_interface_pa; the rms are checked separately against an ODE solution of the
integrals). tau* solves P(|tau| > tau*) = eps with P from tail_ref.py (a line integral across
the disc, mpmath tanh-sinh at 30 digits; a different integral from src/tail.rs's polar form),
and the script stops unless a 45-digit recomputation of ln P(tau*) gives ln eps to 1e-22.

Regenerate:  python3 tests/data/sliding_tail_ref.py > tests/data/sliding_tail_ref.csv
"""
import os
import sys

import mpmath as mp

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # no __pycache__ in tests/data
from tail_ref import ln_p, quantile  # noqa: E402

CASES = [
    ('0', '0', '93870.9726988115', '93870.9726988115'),
    ('0.5', '50000.0', '106808.43856466912', '97869.92182503795'),
    ('1', '100000.0', '138552.84785318474', '108989.94378332855'),
]
EPS = '1e-6'


def main():
    print('mu,m,sx,sy,eps,tau_star')
    for mu, m, sx, sy in CASES:
        args = [mp.mpf(v) for v in (m, sx, sy)]
        with mp.workdps(30):
            t = quantile(*args, mp.mpf(EPS))
        with mp.workdps(45):
            lp = ln_p(*args, t)
            target = mp.log(mp.mpf(EPS))
            assert abs(lp - target) <= mp.mpf('1e-22') * abs(target), (mu, lp)
        print(','.join([mu, m, sx, sy, EPS, mp.nstr(t, 20)]), flush=True)


if __name__ == '__main__':
    main()
