//! Free (non-periodic) boundaries: the contact on a height map that is a window of a larger,
//! unloaded surface, by Hockney's method (R. W. Hockney, Methods Comput. Phys. 9, 1970, 135–211;
//! for contact e.g. Liu, Wang & Liu, Wear 243, 2000, 101–111).
//!
//! # Problem
//! The pressure acts only on the `ny × nx` window of the map (total force p0 · window area); the
//! surface around it is free and unloaded, and the gap is defined only in the window. The
//! displacement at pixel centre i is u_i = Σ_j G(x_i − x_j) p_j with G the displacement at a
//! pixel centre under a unit uniform pressure on one pixel: piecewise-constant pressure,
//! collocation at the centres. The offsets x_i − x_j span (−nx, nx) × (−ny, ny) pixels, so on
//! a `2ny × 2nx` grid with the pressure zero-padded the periodic (FFT) convolution with G
//! placed at the wrapped offsets is exact in the window (the circulant embedding); the padded
//! cells carry zero pressure and their displacements are discarded.
//!
//! # Influence coefficients, computed in real space
//! Paper eqs. 6–7: u_z(q) = 2 S(q)/(q E1*) p(q), E1* the top layer's plane-strain modulus. The
//! kernel is split into
//! - the half-space of the top layer, 2/(q E1*): G is Love's (1929) closed form for a uniformly
//!   loaded rectangle, (1/(π E1*)) ∫∫ dA/r over the pixel ([`love`]), evaluated directly up to
//!   [`LOVE_FAR`] pixel sizes and by 3 × 3 Gauss–Legendre points beyond, where the closed
//!   form's four-corner sum would lose digits (the rule's error there is below 6e−15 relative);
//! - the smooth remainder 2(S(q) − 1)/(q E1*), whose real-space form is the Hankel transform
//!   R(r) = (1/(π E1*)) ∫₀^∞ (S(q) − 1) J0(q r) dq ([`Remainder`]). With x = qD and ρ = r/D (D
//!   the stack's total thickness) and S(x) − 1 = c + a1 x + a2 x² + …, the terms
//!   (c + c1 x + c2 x²) e^{−x} that match this Taylor series to second order are transformed in
//!   closed form (∫ x^k e^{−x} J0(ρx) dx = 1/√(1+ρ²), (1+ρ²)^{−3/2}, (2 − ρ²)(1+ρ²)^{−5/2}),
//!   and the rest, f(x) = O(x³), numerically: composite 8-point Gauss–Legendre on panels of
//!   π/[`RHO_TABLE`] (half a period of J0 at the table's end), tabulated on
//!   ρ = k/[`PER_UNIT`] up to [`RHO_TABLE`] and interpolated by Lagrange polynomials of
//!   degree 7 (the part varies on the scale 1/x of the x ≲ 30 where f lives, so the degree
//!   matters more than the spacing).
//!   Beyond the table the numerical part is taken as 0: a function that is O(x³) at 0 and
//!   analytic has a transform O(ρ^{−5}) (the odd powers contribute nothing and x⁴ gives 9a4/ρ⁵).
//!   The pixel average of R is a 4 × 4 Gauss–Legendre rule on the pixel, subdivided
//!   (quadtree) where the pixel is within two of its sizes of the evaluation point and larger
//!   than D/8, the width on which R varies; beyond [`LOVE_FAR`] pixel sizes the 3 × 3 rule.
//!
//! The kernel's error estimate [`FreeKernel::remainder_error`] is the largest of the tail
//! neglected beyond the table (|f's transform| at the table's end) and the interpolation error
//! (the table against direct quadrature at the midpoints of its last intervals and the first),
//! relative to the self-coefficient.
//!
//! # Interface stresses
//! The transfer functions f(q), g(q) of the interface stresses are applied to the zero-padded
//! pressure on the same doubled grid (`interface_fields_with`): the stress at z = d then
//! includes that of the periodic images of the window, at least one window length L away. For
//! a half-space substrate the normal stress a point load spreads to depth d decays as
//! d³/r⁵ (Boussinesq), so the images contribute a fraction of order (d/L)³ of the load.

use super::fft::Fft2;
use super::{
    BemSettings, BemSolution, Convergence, InterfaceFields, Surface, check_inputs, chunked,
    direction, measure_gap, project, solution, step_denominator, warm_pressure,
};
use crate::error::Error;
use crate::quad::gauss_legendre;
use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;
use serde::Serialize;
use std::f64::consts::PI;

/// The boundary of the map in the contact solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Boundary {
    /// The map is one period of a periodic surface.
    #[default]
    Periodic,
    /// The map is a window of an unloaded surface (Hockney's zero padding).
    Free,
}

impl Boundary {
    pub fn name(self) -> &'static str {
        match self {
            Self::Periodic => "periodic",
            Self::Free => "free",
        }
    }
}

/// Pixel-centre distances (in pixel sizes, the larger of dx and dy) from which both parts of
/// the kernel are averaged over the pixel by the 3 × 3 Gauss–Legendre rule.
pub const LOVE_FAR: f64 = 64.0;

/// End of the remainder's table in ρ = r/D.
pub const RHO_TABLE: f64 = 32.0;

/// Table points per unit of ρ.
pub const PER_UNIT: f64 = 64.0;

/// Points of the Lagrange interpolation in the table (degree 7).
const STENCIL: usize = 8;

/// Gauss–Legendre points per panel of the Hankel quadrature.
const GL_PANEL: usize = 8;

/// The elastic solid under the surface, as the free-boundary kernel needs it.
#[derive(Clone, Copy)]
pub enum Solid<'a> {
    /// A homogeneous half-space of plane-strain modulus `e_star` (Pa).
    HalfSpace { e_star: f64 },
    /// Layers on a half-space: `e_star` the top layer's E* (Pa), `s(q)` the surface compliance
    /// over the top layer's half-space (paper eq. 7, S → 1 as q → ∞), `total` the depth of
    /// the deepest interface and `thinnest` the thinnest layer (m, > 0).
    Layered {
        e_star: f64,
        s: &'a (dyn Fn(f64) -> f64 + Sync),
        thinnest: f64,
        total: f64,
    },
}

/// ∫∫ over the rectangle |ξ| ≤ a, |η| ≤ b of 1/√((x − ξ)² + (y − η)²): Love's (1929) closed
/// form, as the signed sum over the four corners of G(s, t) = sgn(s) sgn(t) F(|s|, |t|),
/// F(s, t) = s asinh(t/s) + t asinh(s/t) = ∫₀^s∫₀^t dA/r.
pub fn love(x: f64, y: f64, a: f64, b: f64) -> f64 {
    let f = |s: f64, t: f64| {
        let (u, v) = (s.abs(), t.abs());
        let mut w = 0.0;
        if u > 0.0 && v > 0.0 {
            w = u * (v / u).asinh() + v * (u / v).asinh();
        }
        w * s.signum() * t.signum()
    };
    f(x + a, y + b) - f(x - a, y + b) - f(x + a, y - b) + f(x - a, y - b)
}

/// The real-space remainder R(r) of a layered kernel (see the module docs), in m/Pa per m²
/// (R times a pixel area is a displacement per unit pressure).
pub struct Remainder {
    e_star: f64,
    total: f64,
    /// c, c1, c2 of the closed-form part.
    coef: [f64; 3],
    /// The numerical part at ρ = k/PER_UNIT.
    table: Vec<f64>,
    /// Estimated absolute error of the numerical part (in the units of the table).
    table_err: f64,
}

impl Remainder {
    /// The remainder of `s(q)` for a stack of total depth `total` whose thinnest layer is
    /// `thinnest` thick (m).
    pub fn new(
        e_star: f64,
        s: &(dyn Fn(f64) -> f64 + Sync),
        thinnest: f64,
        total: f64,
    ) -> Result<Self, Error> {
        if !(thinnest > 0.0 && total >= thinnest && total.is_finite()) {
            return Err(Error::invalid(
                "layer thickness for free boundaries",
                format!("thinnest {thinnest:e} m, total {total:e} m"),
                "layers of finite thickness > 0",
            ));
        }
        let sx = |x: f64| s(x / total);
        // Taylor coefficients of S at 0 by one-sided differences (step h in x = qD).
        let h = 1e-2;
        let v: Vec<f64> = (0..5).map(|k| sx(k as f64 * h)).collect();
        if v.iter().any(|v| !v.is_finite()) {
            return Err(Error::Numerical {
                what: "free-boundary kernel",
                detail: format!("S(q) not finite near q = 0: {v:?}"),
            });
        }
        let c = v[0] - 1.0;
        let a1 = (-25.0 * v[0] + 48.0 * v[1] - 36.0 * v[2] + 16.0 * v[3] - 3.0 * v[4]) / (12.0 * h);
        let a2 = (35.0 * v[0] - 104.0 * v[1] + 114.0 * v[2] - 56.0 * v[3] + 11.0 * v[4])
            / (24.0 * h * h);
        let c1 = a1 + c;
        let c2 = a2 - c / 2.0 + c1;
        let coef = [c, c1, c2];
        // S − 1 decays as e^{−2qd} for the top layer's thickness d; x² e^{−x} below 1e−16 at 45.
        let x_end = 45.0f64.max(25.0 * total / thinnest);
        let width = PI / RHO_TABLE;
        let panels = (x_end / width).ceil() as usize;
        let (gx, gw) = gauss_legendre(GL_PANEL);
        let nodes: Vec<(f64, f64)> = (0..panels)
            .flat_map(|k| {
                let x0 = k as f64 * width;
                gx.iter()
                    .zip(&gw)
                    .map(move |(t, w)| (x0 + 0.5 * width * (t + 1.0), 0.5 * width * w))
            })
            .collect();
        let f: Vec<(f64, f64)> = nodes
            .par_iter()
            .map(|&(x, w)| {
                let fit = (c + c1 * x + c2 * x * x) * (-x).exp();
                (x, w * ((sx(x) - 1.0) - fit))
            })
            .collect();
        if let Some(&(x, _)) = f.iter().find(|(_, v)| !v.is_finite()) {
            return Err(Error::Numerical {
                what: "free-boundary kernel",
                detail: format!("S(q) not finite at q = {:e} 1/m", x / total),
            });
        }
        let transform =
            |rho: f64| -> f64 { f.iter().map(|&(x, wf)| wf * libm::j0(rho * x)).sum::<f64>() };
        let n = (RHO_TABLE * PER_UNIT) as usize;
        let table: Vec<f64> = (0..=n)
            .into_par_iter()
            .map(|k| transform(k as f64 / PER_UNIT))
            .collect();
        let mut rem = Self {
            e_star,
            total,
            coef,
            table,
            table_err: 0.0,
        };
        // Tail beyond the table and interpolation at midpoints of the first and last intervals.
        let mut err = rem.table[n].abs();
        for k in [0, 1, 2, n / 64, n / 16, n / 4, n - 3, n - 2, n - 1] {
            let rho = (k as f64 + 0.5) / PER_UNIT;
            err = err.max((rem.numerical(rho) - transform(rho)).abs());
        }
        rem.table_err = err;
        Ok(rem)
    }

    /// The numerical part at ρ: Lagrange interpolation through the [`STENCIL`] table points
    /// around ρ (the part is even in ρ, so points below 0 mirror those above).
    fn numerical(&self, rho: f64) -> f64 {
        let t = rho * PER_UNIT;
        let n = self.table.len() - 1;
        if t >= n as f64 {
            return 0.0;
        }
        let half = STENCIL / 2;
        let k = (t.floor() as usize).min(n - half);
        let u = t - k as f64;
        let mut acc = 0.0;
        for j in 0..STENCIL {
            let node = j as f64 - (half - 1) as f64;
            let mut w = 1.0;
            for i in 0..STENCIL {
                if i != j {
                    let other = i as f64 - (half - 1) as f64;
                    w *= (u - other) / (node - other);
                }
            }
            let index = (k as isize + node as isize).unsigned_abs();
            acc += w * self.table[index];
        }
        acc
    }

    /// R at distance r (m).
    pub fn at(&self, r: f64) -> f64 {
        let rho = r / self.total;
        let s = 1.0 + rho * rho;
        let [c, c1, c2] = self.coef;
        let closed =
            c / s.sqrt() + c1 / (s * s.sqrt()) + c2 * (2.0 - rho * rho) / (s * s * s.sqrt());
        (closed + self.numerical(rho)) / (PI * self.e_star * self.total)
    }

    /// Estimated absolute error of [`Remainder::at`] (m/Pa per m²).
    pub fn error(&self) -> f64 {
        self.table_err / (PI * self.e_star * self.total)
    }
}

/// 3 × 3 (far) and 4 × 4 (near) Gauss–Legendre nodes on [−1, 1].
fn rules() -> [(Vec<f64>, Vec<f64>); 2] {
    [gauss_legendre(3), gauss_legendre(4)]
}

/// ∫∫ over the box (cx ± a, cy ± b) of R(|x|), for a box whose nearest point may be close to
/// the origin: the 4 × 4 rule, subdivided near the origin until the box is below D/8.
fn remainder_box(
    rem: &Remainder,
    rule: &(Vec<f64>, Vec<f64>),
    c: (f64, f64),
    a: f64,
    b: f64,
) -> f64 {
    let s = a.max(b);
    let dist = c.0.hypot(c.1);
    if dist >= 2.0 * (a + b) || s <= rem.total / 8.0 {
        let (x, w) = rule;
        let mut acc = 0.0;
        for (xi, wi) in x.iter().zip(w) {
            for (yj, wj) in x.iter().zip(w) {
                acc += wi * wj * rem.at((c.0 + a * xi).hypot(c.1 + b * yj));
            }
        }
        return acc * a * b;
    }
    let (ha, hb) = (a / 2.0, b / 2.0);
    [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .iter()
        .map(|(sx, sy)| remainder_box(rem, rule, (c.0 + sx * ha, c.1 + sy * hb), ha, hb))
        .sum()
}

/// The free-boundary influence coefficients on the doubled grid, as the real spectrum of their
/// circulant embedding (column-major over the half spectrum, with the inverse FFT's 1/N).
pub struct FreeKernel {
    nx: usize,
    ny: usize,
    spectrum: Vec<f64>,
    /// The coefficient of a pixel on itself (m/Pa).
    pub self_coefficient: f64,
    /// Estimated error of every coefficient from the remainder's Hankel transform, relative to
    /// the self-coefficient (0 for a half-space).
    pub remainder_error: f64,
}

impl FreeKernel {
    /// The kernel of `solid` for a `ny × nx` window of pixels dx × dy (m).
    pub fn new(
        solid: &Solid,
        (nx, ny): (usize, usize),
        (dx, dy): (f64, f64),
    ) -> Result<Self, Error> {
        let (e_star, rem) = match *solid {
            Solid::HalfSpace { e_star } => (e_star, None),
            Solid::Layered {
                e_star,
                s,
                thinnest,
                total,
            } => (e_star, Some(Remainder::new(e_star, s, thinnest, total)?)),
        };
        if !(e_star.is_finite() && e_star > 0.0) {
            return Err(Error::invalid(
                "modulus E*",
                e_star,
                "a finite E* > 0 in Pa",
            ));
        }
        let (a, b) = (dx / 2.0, dy / 2.0);
        let far = LOVE_FAR * dx.max(dy);
        let [far_rule, near_rule] = rules();
        let love_scale = 1.0 / (PI * e_star);
        // One quadrant of offsets (G is even in each): (ix, iy) in 0..nx × 0..ny.
        let quadrant: Vec<f64> = (0..nx * ny)
            .into_par_iter()
            .map(|i| {
                let (x, y) = ((i % nx) as f64 * dx, (i / nx) as f64 * dy);
                if x.hypot(y) >= far {
                    let (gx, gw) = &far_rule;
                    let mut acc = 0.0;
                    for (xi, wi) in gx.iter().zip(gw) {
                        for (yj, wj) in gx.iter().zip(gw) {
                            let r = (x + a * xi).hypot(y + b * yj);
                            acc +=
                                wi * wj * (love_scale / r + rem.as_ref().map_or(0.0, |m| m.at(r)));
                        }
                    }
                    acc * a * b
                } else {
                    love_scale * love(x, y, a, b)
                        + rem
                            .as_ref()
                            .map_or(0.0, |m| remainder_box(m, &near_rule, (x, y), a, b))
                }
            })
            .collect();
        let self_coefficient = quadrant[0];
        if !quadrant.iter().all(|g| g.is_finite()) {
            return Err(Error::Numerical {
                what: "free-boundary kernel",
                detail: "an influence coefficient is not finite".into(),
            });
        }
        let remainder_error = rem.map_or(0.0, |m| m.error() * dx * dy / self_coefficient);
        let spectrum = embedded_spectrum(&quadrant, nx, ny);
        Ok(Self {
            nx,
            ny,
            spectrum,
            self_coefficient,
            remainder_error,
        })
    }

    /// u ← G ∗ p in the window (p and u `ny × nx`; `pad`, `out` scratch of the doubled grid).
    fn convolve(
        &self,
        plan: &mut Fft2,
        p: &[f64],
        u: &mut [f64],
        pad: &mut [f64],
        out: &mut [f64],
    ) {
        pad_into(p, self.nx, pad);
        let ny2 = 2 * self.ny;
        plan.filter(pad, out, |kx, col| {
            for (c, k) in col.iter_mut().zip(&self.spectrum[kx * ny2..(kx + 1) * ny2]) {
                *c *= *k;
            }
        });
        crop_into(out, self.nx, u);
    }
}

/// `field` (`ny × nx`) into the top-left corner of the zeroed doubled grid `pad`.
fn pad_into(field: &[f64], nx: usize, pad: &mut [f64]) {
    pad.par_chunks_mut(2 * nx).enumerate().for_each(|(y, row)| {
        row.fill(0.0);
        if let Some(src) = field.get(y * nx..(y + 1) * nx) {
            row[..nx].copy_from_slice(src);
        }
    });
}

/// The top-left `ny × nx` window of the doubled grid `pad` into `field`.
fn crop_into(pad: &[f64], nx: usize, field: &mut [f64]) {
    field
        .par_chunks_mut(nx)
        .zip(pad.par_chunks(2 * nx))
        .for_each(|(dst, src)| dst.copy_from_slice(&src[..nx]));
}

/// The real spectrum (the coefficients are even) of the circulant embedding of the quadrant
/// `g[iy * nx + ix]` on the `2ny × 2nx` grid (offset −k at 2n − k; offset ±n unused, 0),
/// column-major over kx in 0..=nx, divided by the grid's size.
fn embedded_spectrum(g: &[f64], nx: usize, ny: usize) -> Vec<f64> {
    let (nx2, ny2) = (2 * nx, 2 * ny);
    let nxc = nx + 1;
    let wrap = |k: usize, n: usize| -> Option<usize> {
        match k {
            k if k < n => Some(k),
            k if k == n => None,
            k => Some(2 * n - k),
        }
    };
    let row_fft = RealFftPlanner::<f64>::new().plan_fft_forward(nx2);
    let mut rows = vec![Complex64::new(0.0, 0.0); ny2 * nxc];
    rows.par_chunks_mut(nxc).enumerate().for_each(|(y, out)| {
        let mut buf: Vec<f64> = (0..nx2)
            .map(|x| match (wrap(x, nx), wrap(y, ny)) {
                (Some(ix), Some(iy)) => g[iy * nx + ix],
                _ => 0.0,
            })
            .collect();
        row_fft
            .process(&mut buf, out)
            .expect("lengths are fixed by the plan");
    });
    let col_fft = FftPlanner::<f64>::new().plan_fft_forward(ny2);
    let inv_n = 1.0 / (nx2 * ny2) as f64;
    let mut spectrum = vec![0.0; nxc * ny2];
    spectrum
        .par_chunks_mut(ny2)
        .enumerate()
        .for_each(|(kx, col)| {
            let mut buf: Vec<Complex64> = (0..ny2).map(|y| rows[y * nxc + kx]).collect();
            col_fft.process(&mut buf);
            for (s, c) in col.iter_mut().zip(&buf) {
                *s = c.re * inv_n;
            }
        });
    spectrum
}

/// Solve the free-boundary contact of a rigid flat with `solid` whose top has the heights of
/// `surface` (the window), at nominal pressure `p0` (total force p0 · window area), from the
/// full contact or the warm start `start`. Same algorithm and stopping test as the periodic
/// solver ([`super::solve_with_compliance`]), with the doubled-grid convolution.
pub fn solve_free(
    surface: &Surface,
    solid: &Solid,
    p0: f64,
    settings: &BemSettings,
    start: Option<&[f64]>,
) -> Result<BemSolution, Error> {
    check_inputs(p0, settings)?;
    let (nx, ny) = (surface.nx, surface.ny);
    let n = nx * ny;
    let kernel = FreeKernel::new(solid, (nx, ny), (surface.dx, surface.dy))?;
    let mut plan = Fft2::new(2 * nx, 2 * ny);
    let (mut pad, mut out) = (vec![0.0; 4 * n], vec![0.0; 4 * n]);
    let mean_h = surface.mean();
    let h: Vec<f64> = surface.heights.iter().map(|v| v - mean_h).collect();
    let tol = settings.gap_tol * surface.h_rms();
    let mut p = match start {
        Some(start) => warm_pressure(start, n, p0)?,
        None => vec![p0; n],
    };
    let (mut u, mut g, mut t, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let (mut g_old, mut restarts, mut iterations) = (1.0, 0usize, 0usize);
    let (mut gap_rms, mut penetration);
    loop {
        kernel.convolve(&mut plan, &p, &mut u, &mut pad, &mut out);
        let (g2, pen, n_c) = measure_gap(&mut g, &u, &h, &p);
        gap_rms = (g2 / n_c).sqrt();
        penetration = pen;
        if (gap_rms <= tol && penetration <= tol) || iterations >= settings.max_iter {
            break;
        }
        iterations += 1;
        let beta = if iterations > 1 { g2 / g_old } else { 0.0 };
        g_old = g2;
        let (mut num, mut sum_t) = direction(&mut t, &g, &p, beta);
        if num <= 0.0 && beta != 0.0 {
            restarts += 1;
            (num, sum_t) = direction(&mut t, &g, &p, 0.0);
        }
        let tbar = sum_t / n_c;
        kernel.convolve(&mut plan, &t, &mut r, &mut pad, &mut out);
        let den = step_denominator(
            "boundary-element contact (free boundaries)",
            &r,
            &t,
            &p,
            tbar,
            iterations,
        )?;
        let (total, _) = project(&mut p, 1.0, &t, &g, num / den, num / den);
        let scale = p0 * n as f64 / total;
        chunked(&mut p, |_, pc| {
            pc.iter_mut().for_each(|pi| *pi *= scale);
            [0.0; 0]
        });
    }
    let convergence = Convergence::of_iteration(iterations, restarts, gap_rms, penetration, tol);
    let sol = solution(surface, p0, p, g, convergence);
    Ok(BemSolution {
        boundary: Boundary::Free,
        ..sol
    })
}

/// A field of the window zero-padded to the doubled grid (`2ny × 2nx`).
pub fn padded(field: &[f64], nx: usize) -> Vec<f64> {
    let mut pad = vec![0.0; 4 * field.len()];
    pad_into(field, nx, &mut pad);
    pad
}

/// The `ny × nx` window of a field on the doubled grid.
pub fn cropped(pad: &[f64], nx: usize) -> Vec<f64> {
    let mut field = vec![0.0; pad.len() / 4];
    crop_into(pad, nx, &mut field);
    field
}

/// Interface fields of a free-boundary solution: the transfer functions applied on the doubled
/// grid to the zero-padded pressure, the window kept (see the module docs).
pub(super) fn interface_fields_with<T>(
    solution: &BemSolution,
    transfer: T,
) -> Result<InterfaceFields, Error>
where
    T: Fn(f64) -> (f64, f64) + Sync,
{
    let nx = solution.nx;
    let doubled = BemSolution {
        nx: 2 * nx,
        ny: 2 * solution.ny,
        pressure: padded(&solution.pressure, nx),
        gap: Vec::new(),
        boundary: Boundary::Periodic,
        ..solution.clone()
    };
    let f = super::interface_fields_with(&doubled, transfer)?;
    let normal = cropped(&f.normal, nx);
    let shear_x = cropped(&f.shear_x, nx);
    let shear_y = cropped(&f.shear_y, nx);
    let magnitude: Vec<f64> = shear_x
        .par_iter()
        .zip(&shear_y)
        .map(|(a, b)| a.hypot(*b))
        .collect();
    Ok(InterfaceFields {
        normal_stats: super::FieldStats::of(&normal),
        shear_stats: super::FieldStats::of(&magnitude),
        normal,
        shear_x,
        shear_y,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫∫ over the box by a 48 × 48 Gauss–Legendre rule (for points outside the box).
    fn brute(x: f64, y: f64, a: f64, b: f64) -> f64 {
        let (gx, gw) = gauss_legendre(48);
        let mut acc = 0.0;
        for (xi, wi) in gx.iter().zip(&gw) {
            for (yj, wj) in gx.iter().zip(&gw) {
                acc += wi * wj / (x - a * xi).hypot(y - b * yj);
            }
        }
        acc * a * b
    }

    #[test]
    fn love_matches_quadrature_and_the_centre_of_a_square() {
        // Centre of a square of side 2a: 8a ln(1 + √2) (Johnson, Contact Mechanics, §3.3).
        let a = 0.7;
        let want = 8.0 * a * (1.0 + 2f64.sqrt()).ln();
        assert!((love(0.0, 0.0, a, a) - want).abs() < 1e-15 * want);
        for &(x, y, a, b) in &[
            (3.0, 0.5, 1.0, 0.5),
            (2.5, -4.0, 0.5, 1.5),
            (-6.0, 7.0, 1.0, 1.0),
            (0.0, 3.0, 1.0, 0.25),
        ] {
            let (l, q) = (love(x, y, a, b), brute(x, y, a, b));
            assert!((l - q).abs() < 1e-12 * q, "({x}, {y}): {l} vs {q}");
        }
        // The far-field rule's 3 × 3 Gauss–Legendre at LOVE_FAR pixel sizes agrees with Love.
        let (gx, gw) = gauss_legendre(3);
        let (x, y) = (LOVE_FAR * 0.8, LOVE_FAR * 0.6);
        let mut g3 = 0.0;
        for (xi, wi) in gx.iter().zip(&gw) {
            for (yj, wj) in gx.iter().zip(&gw) {
                g3 += wi * wj / (x + 0.5 * xi).hypot(y + 0.5 * yj);
            }
        }
        let l = love(x, y, 0.5, 0.5);
        assert!((g3 * 0.25 - l).abs() < 1e-10 * l, "{g3} vs {l}");
    }

    /// S − 1 = c0 e^{−2x} + c1 x e^{−2x} (x = qD) has the Hankel transform (Laplace transforms
    /// of J0) c0/√(4 + ρ²) + 2 c1/(4 + ρ²)^{3/2}: the remainder reproduces it on and beyond
    /// the table within its own error estimate, which is below 1e-6 of |R(0)| (the tail
    /// beyond the table, 6e-7: f's transform at ρ = 32).
    #[test]
    fn remainder_reproduces_a_closed_form_hankel_transform() {
        let (e_star, d, c0, c1) = (3e6, 2e-6, -0.9, 0.7);
        let s = move |q: f64| {
            let x = q * d;
            1.0 + (c0 + c1 * x) * (-2.0 * x).exp()
        };
        let rem = Remainder::new(e_star, &s, d, d).unwrap();
        let exact = |rho: f64| {
            let t = 4.0 + rho * rho;
            (c0 / t.sqrt() + 2.0 * c1 / (t * t.sqrt())) / (PI * e_star * d)
        };
        let scale = exact(0.0).abs();
        assert!(rem.error() < 1e-6 * scale, "{:e}", rem.error() / scale);
        for rho in [0.0, 0.013, 0.5, 1.7, 3.33, 10.01, 31.9, 32.5, 80.0, 1e3] {
            let (got, want) = (rem.at(rho * d), exact(rho));
            assert!(
                (got - want).abs() <= rem.error(),
                "rho = {rho}: {got:e} vs {want:e}"
            );
        }
    }
}
