//! Coarse-to-fine start of the periodic solve: on a large grid, the contact is first solved on
//! the map at half the resolution (itself started the same way), and its pressure, prolonged to
//! the full grid, is the starting point of the full-resolution iteration.
//!
//! The coarse map samples the heights at the even pixels (the same periodic lengths, pixels
//! twice the size); the prolongation is bilinear on the periodic grid (the coarse values at the
//! even pixels, the mean of the two or four coarse neighbours elsewhere), so the starting contact
//! set is the coarse one widened by at most a fine pixel. The coarse solve only needs to find
//! the contact set and the pressure's large-scale shape, so it stops at a looser gap tolerance;
//! the full-resolution solve then converges to the caller's tolerance as from any other start
//! (the contact problem has one solution and the stopping test does not depend on the path).

use super::pool::{self, Buf};
use super::{BemSettings, Surface, solve_from_dyn};

/// Grids with fewer pixels than this are solved from the full contact (a coarse start costs
/// more than it saves there).
const MIN_PIXELS: usize = 512 * 512;

/// Gap tolerance of the coarse solves, relative to h_rms (the caller's, if looser).
const COARSE_GAP_TOL: f64 = 1e-3;

/// The starting pressure of a cold solve on `surface`: the solution on the map at half the
/// resolution (to the looser of [`COARSE_GAP_TOL`] and the caller's tolerance), prolonged to the
/// full grid; `None` where the grid is too small or a side is odd, or if the coarse solve fails
/// (the full-resolution solve then starts from the full contact and reports its own errors).
pub(super) fn coarse_start(
    surface: &Surface,
    compliance: &(dyn Fn(f64) -> f64 + Sync),
    p0: f64,
    settings: &BemSettings,
) -> Option<Buf<f64>> {
    let coarse = coarsen(surface)?;
    let coarse_settings = BemSettings {
        gap_tol: settings.gap_tol.max(COARSE_GAP_TOL),
        ..*settings
    };
    let sol = solve_from_dyn(&coarse, compliance, p0, &coarse_settings, None).ok()?;
    Some(prolong(&sol.pressure, coarse.nx, coarse.ny))
}

/// The map at half the resolution (heights at the even pixels), if the grid is large enough
/// for a coarse start and both sides are even.
fn coarsen(surface: &Surface) -> Option<Surface> {
    let (nx, ny) = (surface.nx, surface.ny);
    if !(nx.is_multiple_of(2) && ny.is_multiple_of(2)) || nx * ny < MIN_PIXELS {
        return None;
    }
    let (cx, cy) = (nx / 2, ny / 2);
    let heights = (0..cy)
        .flat_map(|y| (0..cx).map(move |x| (x, y)))
        .map(|(x, y)| surface.heights[2 * y * nx + 2 * x])
        .collect();
    Surface::new(heights, cx, cy, 2.0 * surface.dx, 2.0 * surface.dy).ok()
}

/// Bilinear prolongation of a coarse `cx × cy` periodic field to the `2cx × 2cy` grid.
fn prolong(coarse: &[f64], cx: usize, cy: usize) -> Buf<f64> {
    let (nx, ny) = (2 * cx, 2 * cy);
    let at = |x: usize, y: usize| coarse[(y % cy) * cx + x % cx];
    let mut fine = pool::F64.take(nx * ny, 0.0);
    for (y, row) in fine.chunks_exact_mut(nx).enumerate() {
        let (y0, odd_y) = (y / 2, y % 2 == 1);
        for (x, v) in row.iter_mut().enumerate() {
            let (x0, odd_x) = (x / 2, x % 2 == 1);
            *v = match (odd_x, odd_y) {
                (false, false) => at(x0, y0),
                (true, false) => 0.5 * (at(x0, y0) + at(x0 + 1, y0)),
                (false, true) => 0.5 * (at(x0, y0) + at(x0, y0 + 1)),
                (true, true) => {
                    0.25 * (at(x0, y0) + at(x0 + 1, y0) + at(x0, y0 + 1) + at(x0 + 1, y0 + 1))
                }
            };
        }
    }
    fine
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarsening_samples_the_even_pixels_of_large_even_grids() {
        let (nx, ny) = (1024, 512);
        let h: Vec<f64> = (0..nx * ny).map(|i| (i % 1000) as f64 * 1e-9).collect();
        let s = Surface::new(h, nx, ny, 1e-6, 2e-6).unwrap();
        let c = coarsen(&s).unwrap();
        assert_eq!((c.nx, c.ny, c.dx, c.dy), (512, 256, 2e-6, 4e-6));
        for (y, x) in [(0, 0), (3, 7), (255, 511)] {
            assert_eq!(c.heights[y * 512 + x], s.heights[2 * y * nx + 2 * x]);
        }
        let odd = Surface::new(vec![0.0; 1023 * 512], 1023, 512, 1e-6, 1e-6).unwrap();
        assert!(coarsen(&odd).is_none());
        let small = Surface::new(vec![0.0; 256 * 256], 256, 256, 1e-6, 1e-6).unwrap();
        assert!(coarsen(&small).is_none());
    }

    #[test]
    fn prolongation_is_bilinear_on_the_periodic_grid() {
        let (cx, cy) = (5, 3);
        let coarse: Vec<f64> = (0..cx * cy).map(|i| (i * i % 7) as f64).collect();
        let c = |x: usize, y: usize| coarse[(y % cy) * cx + x % cx];
        let fine = prolong(&coarse, cx, cy);
        let f = |x: usize, y: usize| fine[y * 2 * cx + x];
        for y in 0..cy {
            for x in 0..cx {
                assert_eq!(f(2 * x, 2 * y), c(x, y));
                assert_eq!(f(2 * x + 1, 2 * y), 0.5 * (c(x, y) + c(x + 1, y)));
                assert_eq!(f(2 * x, 2 * y + 1), 0.5 * (c(x, y) + c(x, y + 1)));
                let mean4 = 0.25 * (c(x, y) + c(x + 1, y) + c(x, y + 1) + c(x + 1, y + 1));
                assert_eq!(f(2 * x + 1, 2 * y + 1), mean4);
            }
        }
        // The mean is kept (each coarse value has weight 4 in the fine sum).
        let (sc, sf) = (coarse.iter().sum::<f64>(), fine.iter().sum::<f64>());
        assert!((sf - 4.0 * sc).abs() < 1e-12 * sf);
    }
}
