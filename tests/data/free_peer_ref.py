"""Peer free-boundary half-space contact on a cropped height map, for tests/it/free_boundary.rs.

Provenance: ContactMechanics (contact.engineering, https://github.com/ContactEngineering/
ContactMechanics, installed with `pip install ContactMechanics`; the commit is written to the CSV)
solves the frictionless, non-adhesive contact of a rigid surface on an elastic half-space with
free boundaries: FreeFFTElasticHalfSpace zero-pads the window to twice its size (Hockney) and uses
Love's influence coefficients of a pixel of uniform pressure; the solve is its constrained
conjugate gradients (Polonsky & Keer) at fixed total force.

The crop: rows 16..16+N, columns 24..24+N (N = 96) of examples/data/height-map.csv (a 128 x 128
map of 0.5 um pixels, heights in m): not periodic. Half-space E* = 4/3 MPa; nominal pressures
p0 below; the total force is p0 times the window's area. A/A0 is the fraction of window pixels
with a positive force.

Run from the repository root: python3 tests/data/free_peer_ref.py > tests/data/free_peer_ref.csv
"""

import numpy as np
import ContactMechanics
from ContactMechanics import FreeFFTElasticHalfSpace
from ContactMechanics.Optimization import constrained_conjugate_gradients

ROW0, COL0, N = 16, 24, 96
DX = 0.5e-6
E_STAR = 1e6 / (1 - 0.5**2)
PRESSURES = [2e4, 5e4]


def main():
    heights = np.loadtxt("examples/data/height-map.csv", delimiter=",", comments="#")
    crop = heights[ROW0:ROW0 + N, COL0:COL0 + N]
    h_rms = crop.std()
    length = N * DX
    print(f"# ContactMechanics {ContactMechanics.__version__}; crop rows {ROW0}..{ROW0 + N}, "
          f"columns {COL0}..{COL0 + N} of examples/data/height-map.csv; E* = {E_STAR!r} Pa")
    print("p0_pa,area_fraction,contact_pixels,mean_contact_pressure_pa")
    for p0 in PRESSURES:
        substrate = FreeFFTElasticHalfSpace((N, N), E_STAR, (length, length))
        sol = constrained_conjugate_gradients(
            substrate, crop, external_force=p0 * length * length,
            pentol=1e-9 * h_rms, maxiter=100000)
        assert sol.success, sol.message
        forces = sol.jac[:N, :N]
        assert abs(sol.jac.sum() - forces.sum()) <= 1e-12 * forces.sum()
        contact = int((forces > 0).sum())
        area = contact / (N * N)
        print(f"{p0!r},{area!r},{contact},{float(forces.sum()) / (contact * DX * DX)!r}")


if __name__ == "__main__":
    main()
