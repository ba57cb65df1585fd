"""Writes the .gwy test files with SurfaceTopography's independent GWY writer.

Run: python3 -m venv /tmp/st && /tmp/st/bin/pip install SurfaceTopography==1.27.1
     /tmp/st/bin/python make_gwy.py
"""
import numpy as np
from SurfaceTopography import Topography, open_topography

# The Gwyddion ASCII export sample as .gwy (3 x 4 points, heights in m).
open_topography("gwyddion-export-english.txt").topography().to_gwy(
    "st-gwyddion-export.gwy", name="My Channel Name"
)

# 5 x 3 points, 2 um x 1.5 um, heights in um, two points masked (not measured).
# SurfaceTopography's arrays are indexed [x, y].
h = np.arange(15.0).reshape(3, 5).T * 0.25 - 1.0
mask = np.zeros_like(h, dtype=bool)
mask[1, 0] = mask[4, 2] = True
Topography(np.ma.masked_array(h, mask), (2.0, 1.5), unit="µm").to_gwy(
    "st-masked.gwy", name="Masked"
)
