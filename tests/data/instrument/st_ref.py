import sys, numpy as np
from SurfaceTopography import open_topography
for f in sys.argv[1:]:
    r = open_topography(f)
    print("==", f, type(r).__name__, "channels:", [c.name for c in r.channels], "default", r.default_channel.index)
    for c in r.channels:
        print("  ch", c.index, repr(c.name), "grid", c.nb_grid_pts, "size", c.physical_sizes, "unit", c.unit, "hsf", c.height_scale_factor, "dim", c.dim)
    t = r.topography()
    h = np.ma.masked_invalid(np.ma.asarray(t.heights()))
    print("  topo", type(t).__name__, "grid", t.nb_grid_pts, "size", repr(t.physical_sizes), "unit", t.unit, "is_uniform", t.is_uniform)
    from SurfaceTopography.Support.UnitConversion import get_unit_conversion_factor
    fac = get_unit_conversion_factor(t.unit, "m")
    hv = h.compressed().astype(float)*fac
    print("  fac", repr(fac), "nmasked", np.ma.count_masked(h), "n", h.size, "h_rms_m %.17g" % np.sqrt(np.mean((hv-hv.mean())**2)), "mean_m %.17g"%hv.mean())
