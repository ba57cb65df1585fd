"""Reference values for tests/it/instrument_bin.rs, from the SurfaceTopography library's readers.

    python3 -m venv /tmp/st && /tmp/st/bin/pip install SurfaceTopography==1.27.1
    /tmp/st/bin/python tests/data/instrument/st_reference.py tests/data/instrument/FILE

For every channel: grid (nx, ny), physical size per axis in the channel's unit, that unit, the
pixel size in m, the number of masked (non-measured) points, the rms about the mean of the
measured heights in m, and four heights in m at (ix, iy) (SurfaceTopography's heights[ix, iy]:
x is the first index). Channels without a length unit for their values (e.g. phase) are listed
with their raw values scaled by the reader's height scale factor, if any.
"""

import sys

import numpy as np
from SurfaceTopography import open_topography

TO_M = {"m": 1.0, "mm": 1e-3, "µm": 1e-6, "um": 1e-6, "nm": 1e-9, "pm": 1e-12}

for path in sys.argv[1:]:
    reader = open_topography(path)
    print(f"== {path}: {type(reader).__name__}, default channel {reader.default_channel.index}")
    for ch in reader.channels:
        unit = ch.unit if isinstance(ch.unit, str) else ch.unit[0]
        f = TO_M.get(unit)
        t = reader.topography(channel_index=ch.index)
        h = t.heights()
        mask = np.ma.getmaskarray(h)
        hv = np.ma.compressed(h) if np.ma.isMaskedArray(h) else h.ravel()
        rms = np.sqrt(np.mean((hv - hv.mean()) ** 2))
        nx, ny = ch.nb_grid_pts
        sx, sy = t.physical_sizes
        print(f"  channel {ch.index} {ch.name!r}: grid ({nx}, {ny}), size ({sx!r}, {sy!r}) {ch.unit}, "
              f"height scale {ch.height_scale_factor!r}")
        print(f"    pixel size m: ({sx / nx * f!r}, {sy / ny * f!r}); masked {int(mask.sum())}")
        scale = f if ch.height_scale_factor is not None else 1.0
        print(f"    rms about the mean: {rms * scale!r} (x {scale})")
        for ix, iy in [(0, 0), (nx - 1, 0), (0, ny - 1), (nx // 2, ny // 3)]:
            v = h[ix, iy]
            print(f"    h[{ix}, {iy}] = {'masked' if mask[ix, iy] else repr(float(v) * scale)}")
