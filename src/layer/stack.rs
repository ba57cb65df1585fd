//! Layer stacks: S and the interface kernels f_k, g_k of N perfectly bonded layers on an elastic
//! half-space (notes.md, "Layer stacks"; for N = 1 these are eq. (7) and the static form of
//! eq. (B7), [`super::Bilayer`]).
//!
//! Geometry: layers k = 1 (top) … N, layer k of material (E_k, ν_k) and thickness d_k ≥ 0, on a
//! substrate half-space; z points into the solid; interface k lies below layer k at depth
//! z_k = d_1 + … + d_k. One Fourier mode of normal stress σ_zz(x, 0) = s0 cos(qx) acts on the
//! frictionless top (σ_xz(x, 0) = 0).
//! - S = u_z(0) q E_1*/(2p): the surface compliance over that of a half-space of the TOP layer's
//!   material (so N = 1 is [`super::Bilayer::response`]'s S, and a homogeneous stack has S = 1).
//! - f_k = σ_zz(z_k)/σ_zz(0), and g_k by σ_xz(x, z_k) = g_k s0 sin(qx) (the phase convention of g).
//!
//! Derivation. Write u_x = U(z) sin qx, u_z = W(z) cos qx, σ_xz = T(z) sin qx,
//! σ_zz = Σ(z) cos qx. Inside a layer (shear modulus G, ν) Hooke's law and equilibrium give a
//! first-order system for y = (Ũ, W̃, T, Σ) with Ũ = 2GqU, W̃ = 2GqW, in ζ = qz:
//!
//! ```text
//! y' = A y,  A = [  0     1   2   0  ]      a = ν/(1−ν),  b = (1−2ν)/(1−ν),  c = 1/(1−ν)
//!                [ −a     0   0   b  ]      (all finite at ν = ½)
//!                [  c     0   0   a  ]
//!                [  0     0  −1   0  ]
//! ```
//!
//! A has the double eigenvalues ±1 and (A² − I)² = 0, so the propagator over a layer of
//! x = q d is exactly exp(xA) = αI + βA + γA² + δA³ with α = cosh x − (x/2) sinh x,
//! β = (3 sinh x − x cosh x)/2, γ = (x/2) sinh x, δ = (x cosh x − sinh x)/2. The solutions that
//! decay downwards (a half-space of the layer's material below a plane) satisfy t = K_d ũ and
//! those that decay upwards t = K_u ũ, with t = (T, Σ), ũ = (Ũ, W̃), κ = 3 − 4ν:
//!
//! ```text
//! K_d = −[2(1−ν)  1−2ν; 1−2ν  2(1−ν)]/κ,   K_u = [2(1−ν)  −(1−2ν); −(1−2ν)  2(1−ν)]/κ,
//! K_u − K_d = 4(1−ν)/κ · I,
//! ```
//!
//! and along them y moves as e^{∓x}(I ± x(A ± I)), i.e. ũ as E_d = e^{−x}(I + (x/κ)[−1 1; −1 1])
//! downwards and E_u = e^{−x}(I + (x/κ)[−1 −1; 1 1]) upwards.
//!
//! Recursion. Let K be the stiffness of everything below a plane, t = K q·u, in Pa (K_d·2G_s for
//! the substrate); in layer k's units it is K̃ = K/(2G_k), negative definite and symmetric
//! (reciprocity). From the bottom up, each layer maps the K̃_b below it to the K̃_t above it:
//! - thick layers (x > 1), with only decaying exponentials: the field is a downward-decaying part
//!   with top displacement v plus an upward-decaying part with bottom displacement w. The bottom
//!   condition gives w = R v, R = (K_u − K̃_b)⁻¹(K̃_b − K_d) E_d; with ER = E_u R,
//!   K̃_t = K_d + (K_u − K_d) ER (I + ER)⁻¹ (a correction O(x² e^{−2x}) to the half-space), and the
//!   bottom displacement is ũ_b = B v, B = (K_u − K̃_b)⁻¹(K_u − K_d) E_d, a product of sums of
//!   definite matrices that does not cancel however stiff or soft the base;
//! - thin layers (x ≤ 1), with the propagator: y_t = Q y_b, Q = exp(−xA) (α, γ even and β, δ odd
//!   in x, each by its Taylor series, whose terms past the first have one sign), so
//!   K̃_t = X Y⁻¹ with X = Q_tu + Q_tt K̃_b, Y = Q_uu + Q_ut K̃_b (for a thin layer Q_uu ≈ I,
//!   Q_tt ≈ I, and the layer's compliance and membrane stiffness enter with the sign of K̃_b:
//!   nothing cancels at modulus ratios 1e±8 either way). At x = 0 this is K̃_t = K̃_b exactly.
//!
//! The off-diagonal entries of K̃_t are computed twice (the two off-diagonal entries of the last
//! product) and the one with the smaller cancellation ratio Σ|terms|/|sum| is kept for both:
//! K is symmetric, and one of the two loses digits when the layer's and the base's couplings
//! nearly cancel (a soft layer between two stiff ones at q d ≈ 0.02 lost 1e−11 otherwise).
//!
//! Stresses. From the top, t(0) = (0, 1) and ũ(0) = K̃_1⁻¹ t(0) = (I + ER)(K_d + K_u ER)⁻¹ t(0)
//! (K̃_t (I + ER) = K_d + K_u ER, as K_u − K_d is a multiple of I: the top layer's stiffness
//! itself is not formed), or Y X⁻¹ t(0) if layer 1 is thin (S = −W̃(0)/(2(1 − ν_1))); down
//! through each layer, given the state (ũ_t, t_t) at its top:
//! - thick: v = (K_d + K_u ER)⁻¹ t_t, ũ_b = B v, t_b = K̃_b ũ_b;
//! - thin: two forms of each component of ũ_b (X⁻¹ t_t, and ũ_t + (P_uu − I)ũ_t + P_ut t_t with
//!   P = exp(xA)) and of t_b (K̃_b ũ_b, and t_t + P_tu ũ_t + (P_tt − I) t_t), each component taken
//!   from the form with the smaller cancellation ratio. A stiff thin plate on a soft base carries
//!   the load in bending (t_b ≪ t_t: the second form cancels, the first does not); a thin layer
//!   on a matching or stiffer base passes t nearly unchanged with g_k ∝ q z_k (the first form
//!   cancels, the second does not).
//!
//! Accuracy: against a 120/160-digit solution of the whole boundary-value problem
//! (`tests/data/stack_ref.py`: N = 1–4 and 10, neighbour modulus ratios 1e±8, ν = 0 … ½, q z_k
//! from 1e−8 to 1e4) the worst relative error of S, f_k, g_k is below [`STACK_RTOL`] wherever the
//! value's magnitude is at least 1e−30. For x > ~745, e^{−x} underflows and the thick step
//! returns the half-space: the interface stresses below are then below 1e−300.

mod tangential;

pub use tangential::InterfaceShear;

use super::Elastic;
use crate::error::Error;
use crate::simd::with_avx2;
use serde::Serialize;
use std::cell::RefCell;
use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::mem::take;

/// Relative error bound of [`Stack::response`]'s S, f_k and g_k where their magnitude is at
/// least 1e−30, as asserted by the test against the high-precision reference (measured worst:
/// 4e−13).
pub const STACK_RTOL: f64 = 1e-11;

/// The most layers a stack may have (the range the accuracy is tested on).
pub const MAX_LAYERS: usize = 10;

/// Above this q·d a layer is "thick" (decaying-exponential step), at or below "thin" (series).
const X_THIN: f64 = 1.0;

/// Above this q·d_1 the top layer hides everything below it from S ([`Stack::s_far`]).
const X_FAR: f64 = 40.0;

/// Taylor terms of the propagator coefficients, enough for x ≤ 1 (the first left out is below
/// 1e−20 of the sum).
const TERMS: usize = 10;

type M2 = [[f64; 2]; 2];
type V2 = [f64; 2];
type M4 = [[f64; 4]; 4];

/// Series coefficients (k = 0 … TERMS−1), all positive:
/// α − 1 = −x⁴ Σ (k+1) x^{2k}/(2k+4)!,  β − x = −x⁵ Σ (k+1) x^{2k}/(2k+5)!,
/// γ = x² Σ x^{2k}/(2(2k+1)!),  δ = x³ Σ (k+1) x^{2k}/(2k+3)!.
const fn series(first: usize, weighted: bool, half: bool) -> [f64; TERMS] {
    let mut c = [0.0; TERMS];
    let mut k = 0;
    while k < TERMS {
        let n = 2 * k + first;
        let mut fact = 1.0;
        let mut i = 2;
        while i <= n {
            fact *= i as f64;
            i += 1;
        }
        let w = if weighted { (k + 1) as f64 } else { 1.0 };
        c[k] = w / fact / if half { 2.0 } else { 1.0 };
        k += 1;
    }
    c
}

/// The four series' coefficients side by side, term k in row k: (α − 1, β − x, γ, δ) as above.
const SERIES: [[f64; 4]; TERMS] = {
    let s = [
        series(4, true, false),
        series(5, true, false),
        series(1, false, true),
        series(3, true, false),
    ];
    let mut c = [[0.0; 4]; TERMS];
    let mut k = 0;
    while k < TERMS {
        let mut j = 0;
        while j < 4 {
            c[k][j] = s[j][k];
            j += 1;
        }
        k += 1;
    }
    c
};

/// The four series' sums in x² (each by Horner's rule, the four side by side).
#[inline(always)]
fn horner4(x2: f64) -> [f64; 4] {
    SERIES.iter().rev().fold([0.0; 4], |acc, ck| {
        [
            acc[0] * x2 + ck[0],
            acc[1] * x2 + ck[1],
            acc[2] * x2 + ck[2],
            acc[3] * x2 + ck[3],
        ]
    })
}

#[inline(always)]
fn mul(a: &M2, b: &M2) -> M2 {
    [
        [
            a[0][0] * b[0][0] + a[0][1] * b[1][0],
            a[0][0] * b[0][1] + a[0][1] * b[1][1],
        ],
        [
            a[1][0] * b[0][0] + a[1][1] * b[1][0],
            a[1][0] * b[0][1] + a[1][1] * b[1][1],
        ],
    ]
}

#[inline(always)]
fn mulv(a: &M2, v: V2) -> V2 {
    [
        a[0][0] * v[0] + a[0][1] * v[1],
        a[1][0] * v[0] + a[1][1] * v[1],
    ]
}

#[inline(always)]
fn add(a: &M2, b: &M2) -> M2 {
    [
        [a[0][0] + b[0][0], a[0][1] + b[0][1]],
        [a[1][0] + b[1][0], a[1][1] + b[1][1]],
    ]
}

#[inline(always)]
fn sub(a: &M2, b: &M2) -> M2 {
    [
        [a[0][0] - b[0][0], a[0][1] - b[0][1]],
        [a[1][0] - b[1][0], a[1][1] - b[1][1]],
    ]
}

#[inline(always)]
fn scale(a: &M2, s: f64) -> M2 {
    [[a[0][0] * s, a[0][1] * s], [a[1][0] * s, a[1][1] * s]]
}

#[inline(always)]
fn inv(a: &M2) -> M2 {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [
        [a[1][1] / det, -a[0][1] / det],
        [-a[1][0] / det, a[0][0] / det],
    ]
}

const I2: M2 = [[1.0, 0.0], [0.0, 1.0]];

/// Σ|terms| / |sum|: how many times the rounding of the terms is magnified in their sum
/// (1 for an exact zero of zero terms, infinite for a zero of others). `terms` is the sum of
/// the terms' magnitudes in the order of `sum`'s, so it is at least |sum| (rounding is
/// monotone) and the quotient at least 1: taking the larger of it and 1 changes nothing but
/// 0/0, which it makes 1, without a branch (the quotients of a comparison are formed side by
/// side).
#[inline(always)]
fn ratio(terms: f64, sum: f64) -> f64 {
    (terms / sum.abs()).max(1.0)
}

/// The product a·b of a symmetric result: both off-diagonal entries from whichever of the two
/// computed ones cancels less.
#[inline(always)]
fn mul_sym(a: &M2, b: &M2) -> M2 {
    let c = mul(a, b);
    let r01 = ratio(
        (a[0][0] * b[0][1]).abs() + (a[0][1] * b[1][1]).abs(),
        c[0][1],
    );
    let r10 = ratio(
        (a[1][0] * b[0][0]).abs() + (a[1][1] * b[1][0]).abs(),
        c[1][0],
    );
    let off = if r01 <= r10 { c[0][1] } else { c[1][0] };
    [[c[0][0], off], [off, c[1][1]]]
}

/// Per component, the value of `a` or `b` whose cancellation ratio is smaller.
#[inline(always)]
fn pick(a: (V2, V2), b: (V2, V2)) -> V2 {
    let (va, ta) = a;
    let (vb, tb) = b;
    let choose = |i: usize| {
        if ratio(ta[i], va[i]) <= ratio(tb[i], vb[i]) {
            va[i]
        } else {
            vb[i]
        }
    };
    [choose(0), choose(1)]
}

/// m·v + w with the sums of the magnitudes of each component's terms.
#[inline(always)]
fn mulv_add_terms(m: &M2, v: V2, w: V2) -> (V2, V2) {
    let val = [
        m[0][0] * v[0] + m[0][1] * v[1] + w[0],
        m[1][0] * v[0] + m[1][1] * v[1] + w[1],
    ];
    let terms = [
        (m[0][0] * v[0]).abs() + (m[0][1] * v[1]).abs() + w[0].abs(),
        (m[1][0] * v[0]).abs() + (m[1][1] * v[1]).abs() + w[1].abs(),
    ];
    (val, terms)
}

fn mul4(a: &M4, b: &M4) -> M4 {
    let mut c = [[0.0; 4]; 4];
    for (ci, ai) in c.iter_mut().zip(a) {
        for (j, cij) in ci.iter_mut().enumerate() {
            *cij = (0..4).map(|k| ai[k] * b[k][j]).sum();
        }
    }
    c
}

/// The 2×2 blocks (uu, ut, tu, tt) of a 4×4 matrix on (ũ, t).
#[inline(always)]
fn blocks(m: &M4) -> [M2; 4] {
    let b = |r: usize, c: usize| [[m[r][c], m[r][c + 1]], [m[r + 1][c], m[r + 1][c + 1]]];
    [b(0, 0), b(0, 2), b(2, 0), b(2, 2)]
}

/// One layer of a stack: its material and thickness (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Layer {
    pub material: Elastic,
    pub thickness: f64,
}

/// The thickness-independent constants of one layer's material.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Consts {
    /// 2G (Pa): converts between the stiffness in Pa and in the layer's units.
    two_g: f64,
    /// 1/(2G), formed once (the recursions scale by it at every node).
    inv_two_g: f64,
    kappa: f64,
    /// A, A², A³ of the first-order system.
    powers: [M4; 3],
    kd: M2,
    ku: M2,
}

impl Consts {
    fn new(m: &Elastic) -> Self {
        let nu = m.poisson;
        let (a, b, c) = (
            nu / (1.0 - nu),
            (1.0 - 2.0 * nu) / (1.0 - nu),
            1.0 / (1.0 - nu),
        );
        let a1 = [
            [0.0, 1.0, 2.0, 0.0],
            [-a, 0.0, 0.0, b],
            [c, 0.0, 0.0, a],
            [0.0, 0.0, -1.0, 0.0],
        ];
        let a2 = mul4(&a1, &a1);
        let a3 = mul4(&a2, &a1);
        let kappa = 3.0 - 4.0 * nu;
        let (p, o) = (2.0 * (1.0 - nu) / kappa, (1.0 - 2.0 * nu) / kappa);
        let two_g = 2.0 * m.shear_modulus();
        Self {
            two_g,
            inv_two_g: 1.0 / two_g,
            kappa,
            powers: [a1, a2, a3],
            kd: [[-p, -o], [-o, -p]],
            ku: [[p, -o], [-o, p]],
        }
    }

    /// 4(1 − ν)/κ: K_u − K_d = this times I.
    fn ku_minus_kd(&self) -> f64 {
        2.0 * self.ku[0][0]
    }

    /// The blocks of exp(xA) − I and exp(−xA) − I for 0 ≤ x ≤ 1 (P − I and Q − I), from one set
    /// of series: the odd terms change sign, each term is formed once. A and A³ couple (Ũ, Σ)
    /// only with (W̃, T) and A² only within each pair ([`cross`]), so an entry of P − I is
    /// either odd (β A + δ A³, negated in Q) or even ((α − 1) I + γ A², the same in Q): the sums
    /// of the full four-term form with its exact zeros left out.
    #[inline(always)]
    fn propagators_minus_i(&self, x: f64) -> ([M2; 4], [M2; 4]) {
        let x2 = x * x;
        let [h_a, h_b, h_g, h_d] = horner4(x2);
        let am1 = -x2 * x2 * h_a;
        let beta = x - x2 * x2 * x * h_b;
        let gamma = x2 * h_g;
        let delta = x2 * x * h_d;
        let [a1, a2, a3] = &self.powers;
        let (mut p, mut q) = ([[0.0; 4]; 4], [[0.0; 4]; 4]);
        for i in 0..4 {
            for j in 0..4 {
                if cross(i, j) {
                    let odd = 0.0 + beta * a1[i][j] + delta * a3[i][j];
                    p[i][j] = odd;
                    q[i][j] = 0.0 - odd;
                } else {
                    let diag = if i == j { am1 } else { 0.0 };
                    let even = diag + 0.0 + gamma * a2[i][j];
                    p[i][j] = even;
                    q[i][j] = even;
                }
            }
        }
        (blocks(&p), blocks(&q))
    }
}

/// Whether the entry (i, j) of a 4×4 matrix on (Ũ, W̃, T, Σ) couples (Ũ, Σ) with (W̃, T): A
/// and A³ have only such entries, I and A² none.
const fn cross(i: usize, j: usize) -> bool {
    (i == 0 || i == 3) != (j == 0 || j == 3)
}

/// What the downward pass needs of one layer, in that layer's units.
#[derive(Debug, Clone, Copy)]
enum Step {
    Thin {
        kb: M2,
        x_inv: M2,
        y: M2,
        /// The blocks (uu, ut, tu, tt) of exp(xA) − I.
        p: [M2; 4],
    },
    Thick {
        kb: M2,
        /// (K̃_t (I + ER))⁻¹ = (K_d + K_u ER)⁻¹: top traction to the downward part's
        /// displacement.
        v_of_t: M2,
        b: M2,
        /// I + ER: the downward part's displacement to the top displacement.
        i_er: M2,
    },
}

/// S and, at every interface (top first), f_k and g_k at one q.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StackResponse {
    pub s: f64,
    /// (f_k, g_k) for k = 1 … N.
    pub interfaces: Vec<(f64, f64)>,
}

/// N perfectly bonded layers (top first) on a substrate half-space.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    layers: Vec<Layer>,
    substrate: Elastic,
    consts: Vec<Consts>,
    sub_consts: Consts,
}

impl Stack {
    /// A stack of 1 to [`MAX_LAYERS`] layers, each of finite thickness ≥ 0 (a zero-thickness
    /// layer is allowed and has no effect).
    pub fn new(layers: Vec<Layer>, substrate: Elastic) -> Result<Self, Error> {
        if layers.is_empty() || layers.len() > MAX_LAYERS {
            return Err(Error::invalid(
                "number of layers",
                layers.len(),
                "1 to 10 layers",
            ));
        }
        for l in &layers {
            Elastic::new(l.material.youngs, l.material.poisson)?;
            if !(l.thickness.is_finite() && l.thickness >= 0.0) {
                return Err(Error::invalid(
                    "layer thickness",
                    l.thickness,
                    "a finite thickness >= 0 in m",
                ));
            }
        }
        Elastic::new(substrate.youngs, substrate.poisson)?;
        let consts = layers.iter().map(|l| Consts::new(&l.material)).collect();
        Ok(Self {
            consts,
            sub_consts: Consts::new(&substrate),
            layers,
            substrate,
        })
    }

    pub fn layers(&self) -> &[Layer] {
        &self.layers
    }

    pub fn substrate(&self) -> Elastic {
        self.substrate
    }

    /// Depths z_k of the interfaces (m), top first.
    pub fn depths(&self) -> Vec<f64> {
        self.layers
            .iter()
            .scan(0.0, |z, l| {
                *z += l.thickness;
                Some(*z)
            })
            .collect()
    }

    /// S, f_k, g_k at wavenumber q ≥ 0 (1/m).
    pub fn response(&self, q: f64) -> StackResponse {
        let mut interfaces = vec![(0.0, 0.0); self.layers.len()];
        let s = self.response_into(q, &mut interfaces);
        StackResponse { s, interfaces }
    }

    /// S at q, with (f_k, g_k) written to `out` (length N): [`Stack::response`] without
    /// allocating.
    pub fn response_into(&self, q: f64, out: &mut [(f64, f64)]) -> f64 {
        debug_assert!(q >= 0.0 && out.len() == self.layers.len());
        let n = self.layers.len();
        let mut steps = [EMPTY_STEP; MAX_LAYERS];
        self.up_to_top(q, self.substrate_stiffness(), &mut steps[..n]);
        self.down(&steps[..n], &[], out)
    }

    /// The substrate's stiffness t = K q·u (Pa).
    fn substrate_stiffness(&self) -> M2 {
        let sub = &self.sub_consts;
        scale(&sub.kd, sub.two_g)
    }

    /// The upward recursion through the layers `from` … `from + steps.len() − 1`, starting from
    /// the stiffness `k_pa` (Pa) below the last of them: each layer's step into `steps`, and
    /// the stiffness (Pa) above the first.
    #[inline(always)]
    fn up(&self, q: f64, from: usize, mut k_pa: M2, steps: &mut [Step]) -> M2 {
        let range = from..from + steps.len();
        let layers = self.layers[range.clone()].iter().zip(&self.consts[range]);
        for (step, (layer, c)) in steps.iter_mut().zip(layers).rev() {
            let kb = scale(&k_pa, c.inv_two_g);
            let x = q * layer.thickness;
            let kt = if x <= X_THIN {
                thin_up(c, x, kb, step)
            } else {
                thick_up(c, x, &Face::new(c, kb), step)
            };
            k_pa = scale(&kt, c.two_g);
        }
        k_pa
    }

    /// [`Self::up`] through layers 0 … `steps.len() − 1` (not none) from the stiffness `k_pa`
    /// (Pa) below the last of them, without the top layer's stiffness: the top displacement
    /// comes from the top layer's step ([`Self::top_displacement`]).
    #[inline(always)]
    fn up_to_top(&self, q: f64, k_pa: M2, steps: &mut [Step]) {
        let (top, below) = steps.split_first_mut().expect("a layer");
        let k_pa = self.up(q, 1, k_pa, below);
        let c = &self.consts[0];
        let kb = scale(&k_pa, c.inv_two_g);
        let x = q * self.layers[0].thickness;
        if x <= X_THIN {
            thin_step(c, x, kb, top);
        } else {
            thick_step(c, x, &Face::new(c, kb), top);
        }
    }

    /// [`Self::up_to_top`] through layers 0 … `steps.len() − 1` from the top of the base, the
    /// lowest of them on its face `face` to the base.
    #[inline(always)]
    fn up_from_face(&self, q: f64, face: &Face, steps: &mut [Step]) {
        let (last, above) = steps.split_last_mut().expect("a layer above the base");
        let c = &self.consts[above.len()];
        let x = q * self.layers[above.len()].thickness;
        let thin = x <= X_THIN;
        if above.is_empty() {
            if thin {
                thin_step(c, x, face.kb, last);
            } else {
                thick_step(c, x, face, last);
            }
            return;
        }
        let kt = if thin {
            thin_up(c, x, face.kb, last)
        } else {
            thick_up(c, x, face, last)
        };
        self.up_to_top(q, scale(&kt, c.two_g), above);
    }

    /// The downward pass from the top through the steps of every layer (`upper`, not empty,
    /// then `lower`; top first): S, and (f_k, g_k) into `out`.
    fn down(&self, upper: &[Step], lower: &[Step], out: &mut [(f64, f64)]) -> f64 {
        let u0 = self.top_displacement(&upper[0], [0.0, 1.0]);
        self.interfaces_from(u0, upper, lower, out);
        self.s_of(u0)
    }

    /// S where the top layer is far thicker than the wavelength, x = q·d_1 > [`X_FAR`]: the
    /// top layer's half-space's, ũ(0) = K_d⁻¹ t(0), whatever lies below. The thick step's
    /// ũ(0) = (I + ER)(K_d + K_u ER)⁻¹ t(0) differs from it only through ER = E_u R₀ E_d, and
    /// ‖ER‖ ≤ 5(1 + 2x)² e^{−2x} < 6e−31: ‖E_u‖, ‖E_d‖ ≤ e^{−x}(1 + 2x/κ) with κ ≥ 1, and
    /// R₀ = (K_u − K̃_b)⁻¹(K̃_b − K_d) = −I + (K_u − K_d)(K_u − K̃_b)⁻¹ has norm at most
    /// 1 + 4(1 − ν) ≤ 5 for any base (K_u − K̃_b is symmetric with eigenvalues ≥ 1/κ, K̃_b being
    /// negative definite; K_u − K_d = 4(1 − ν)/κ·I). Beside the entries of K_d (2/3 … 1 on the
    /// diagonal) and of I, such terms round away: this is the step's S to the last bit, but for
    /// a rounding a perturbation of 1e−30 relative can flip (one ulp, far inside
    /// [`STACK_RTOL`]). Checked bit for bit against the recursion at neighbour modulus ratios
    /// 1e±8 (`tests/it/stack.rs`).
    fn s_far(&self) -> f64 {
        self.s_of(mulv(&inv(&self.consts[0].kd), [0.0, 1.0]))
    }

    /// S from the top displacement ũ(0) (in the top layer's units) under t(0) = (0, 1).
    #[inline(always)]
    fn s_of(&self, u0: V2) -> f64 {
        -u0[1] / (2.0 * (1.0 - self.layers[0].material.poisson))
    }

    /// The top displacement ũ(0) (in the top layer's units) under the top traction t(0) = `t0`,
    /// from the top layer's step.
    #[inline(always)]
    fn top_displacement(&self, top_step: &Step, t0: V2) -> V2 {
        // Y X⁻¹ for a thin top layer (no inversion of the stiffness, which cancels for a thin
        // incompressible layer on a far stiffer base), K̃_1⁻¹ = (I + ER)(K̃_1 (I + ER))⁻¹ for a
        // thick one.
        match top_step {
            Step::Thin { x_inv, y, .. } => mulv(y, mulv(x_inv, t0)),
            Step::Thick { v_of_t, i_er, .. } => mulv(i_er, mulv(v_of_t, t0)),
        }
    }

    /// (f_k, g_k) into `out` from the top displacement `u0` under t(0) = (0, 1), through the
    /// steps of every layer (`upper`, not empty, then `lower`; top first).
    #[inline(always)]
    fn interfaces_from(&self, u0: V2, upper: &[Step], lower: &[Step], out: &mut [(f64, f64)]) {
        let mut t = [[0.0; 2]; MAX_LAYERS];
        self.pass(
            u0,
            upper.iter().chain(lower),
            [0.0, 1.0],
            &mut t[..out.len()],
        );
        for (o, t) in out.iter_mut().zip(&t) {
            *o = (t[1], t[0]);
        }
    }

    /// The downward pass of the top traction t(0) = `t0` with the top displacement `u0` (in the
    /// top layer's units) through the steps of every layer (top first): the traction (T, Σ) at
    /// every interface into `out`.
    #[inline(always)]
    fn pass<'a>(&self, u0: V2, steps: impl Iterator<Item = &'a Step>, t0: V2, out: &mut [V2]) {
        let mut t = t0;
        // Displacement times q (dimensionless): layer k's ũ is 2G_k times this.
        let mut uq = scale_v(u0, self.consts[0].inv_two_g);
        for ((step, c), o) in steps.zip(&self.consts).zip(out.iter_mut()) {
            let ut = scale_v(uq, c.two_g);
            let (ub, tb) = down(step, ut, t);
            *o = tb;
            t = tb;
            uq = scale_v(ub, c.inv_two_g);
        }
    }
}

/// A hash of a wavenumber's bits for the per-node caches: a multiplication and a fold, enough
/// for keys that are quadrature nodes (the default SipHash cost more than the kernels).
#[derive(Debug, Default, Clone, Copy)]
pub struct NodeHasher(u64);

impl Hasher for NodeHasher {
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(self.0.rotate_left(8) ^ u64::from(b));
        }
    }

    fn write_u64(&mut self, k: u64) {
        let h = k.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        self.0 = h ^ (h >> 32);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// A map from a wavenumber's bits to an index, hashed by [`NodeHasher`].
pub type NodeMap = HashMap<u64, u32, BuildHasherDefault<NodeHasher>>;

/// S of the stack served at one wavenumber of a [`StackCache`], valid if computed in the
/// cache's current `generation`.
#[derive(Debug, Clone, Copy)]
struct NodeS {
    generation: u64,
    s: f64,
}

/// Up to this q·d_1 the cache forms the interface kernels with S, from the steps just formed;
/// above it S alone, and the interface kernels (steps formed again) only if asked for. The
/// contact integrals ask for them up to their tails' cut, from q·z_k = 20 on by a few panels
/// (`contact::evaluate`), and z_1 = d_1 is the shallowest interface: past this they are
/// rarely asked for, below it mostly.
const X_EAGER: f64 = 30.0;

/// The kernels of a stack whose layers change thickness (or material) above a fixed base, per
/// wavenumber: the base (the layers below the `varied` one and the substrate) is the same for
/// every stack served, so its part of the upward recursion (its steps and the varied layer's
/// face to it) is computed once per wavenumber and kept; each stack's own part (the layers from
/// the top down to the varied one) is formed once per wavenumber for S, and with it the
/// downward pass (the interface kernels) where q·d_1 ≤ 30 (`X_EAGER`); above that the interface
/// kernels are formed only at the wavenumbers where they are asked for (the contact integrals
/// ask for S alone above the interface tails' cut). S and the interface kernels are kept until
/// the next stack; the steps above the base are not kept. The same operations as
/// [`Stack::response_into`] in the same order, so the same values to the last bit, but for S
/// where q·d_1 > 40: the top layer's half-space's (formed once per stack: the layers below are
/// far from S there; the steps and the base are then formed only if the interface kernels are
/// asked for).
///
/// The base follows the stacks served ([`StackCache::serve`]): a stack that differs from the
/// last one below the varied layer, in the varied layer's material (the faces are that
/// material's), or in the number of layers or the substrate, starts a new base below the
/// deepest layer that differs (the top layer's when the stacks are unrelated).
#[derive(Debug, Clone)]
pub struct StackCache {
    stack: Stack,
    /// S of the top layer's half-space ([`Stack::s_far`]).
    s_far: f64,
    varied: usize,
    generation: u64,
    index: NodeMap,
    /// The wavenumbers' bits, in the order kept.
    keys: Vec<u64>,
    /// The node last asked for: the evaluations ask for the nodes in the same order every time,
    /// so the next one is usually the node after it, found without hashing.
    cursor: usize,
    /// Per node, S of the current stack.
    s: Vec<NodeS>,
    /// Per node, the generation in which its interface kernels were computed.
    fg_generation: Vec<u64>,
    /// Per node, the varied layer's face to the base (formed with the base's steps when first
    /// needed).
    faces: Vec<Option<Face>>,
    /// Per node, the steps of the base's layers (top first), `stack.layers.len() − varied − 1`
    /// of them.
    base_steps: Vec<Step>,
    /// Per node, (f_k, g_k) of the current stack, `stack.layers.len()` of them.
    interfaces: Vec<(f64, f64)>,
    /// The steps of the current stack's layers above the base (top first) at the node being
    /// computed, `varied + 1` of them.
    upper: [Step; MAX_LAYERS],
}

/// The per-node storage of a [`StackCache`], emptied, kept for the next cache on the thread.
#[derive(Default)]
struct Spare {
    index: NodeMap,
    keys: Vec<u64>,
    s: Vec<NodeS>,
    fg_generation: Vec<u64>,
    faces: Vec<Option<Face>>,
    base_steps: Vec<Step>,
    interfaces: Vec<(f64, f64)>,
}

thread_local! {
    /// The storage of the last cache dropped on this thread. A check builds a new engine, and
    /// with it a new cache of some MB: taken fresh from the allocator every time, these pages
    /// were returned to the system and faulted in again at every check.
    static SPARE: RefCell<Option<Spare>> = const { RefCell::new(None) };
}

impl Drop for StackCache {
    fn drop(&mut self) {
        self.clear_nodes();
        let spare = Spare {
            index: take(&mut self.index),
            keys: take(&mut self.keys),
            s: take(&mut self.s),
            fg_generation: take(&mut self.fg_generation),
            faces: take(&mut self.faces),
            base_steps: take(&mut self.base_steps),
            interfaces: take(&mut self.interfaces),
        };
        // After the thread's storage is gone (at its exit) the spare is simply freed.
        let _ = SPARE.try_with(|s| *s.borrow_mut() = Some(spare));
    }
}

impl StackCache {
    /// Forgets every node, keeping the storage.
    fn clear_nodes(&mut self) {
        self.index.clear();
        self.keys.clear();
        self.s.clear();
        self.fg_generation.clear();
        self.faces.clear();
        self.base_steps.clear();
        self.interfaces.clear();
    }

    /// A cache serving `stack`, with the base below its top layer (on the storage of the last
    /// cache dropped on this thread, if any).
    pub fn new(stack: Stack) -> Self {
        let spare = SPARE
            .try_with(|s| s.borrow_mut().take())
            .ok()
            .flatten()
            .unwrap_or_default();
        Self {
            s_far: stack.s_far(),
            stack,
            varied: 0,
            generation: 1,
            index: spare.index,
            keys: spare.keys,
            cursor: 0,
            s: spare.s,
            fg_generation: spare.fg_generation,
            faces: spare.faces,
            base_steps: spare.base_steps,
            interfaces: spare.interfaces,
            upper: [EMPTY_STEP; MAX_LAYERS],
        }
    }

    /// The stack served.
    pub fn stack(&self) -> &Stack {
        &self.stack
    }

    /// The layer (index, 0 = top) above the base: the deepest layer that may change.
    pub fn varied(&self) -> usize {
        self.varied
    }

    /// How many wavenumbers are kept.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// Whether no wavenumber is kept.
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// Serve `stack` from now on: the responses kept are dropped unless it is the stack served,
    /// the base is kept if it is `stack`'s too and the varied layer's material is unchanged
    /// (the faces kept depend on it); otherwise everything kept is dropped.
    pub fn serve(&mut self, stack: &Stack) {
        if *stack == self.stack {
            return;
        }
        let related = stack.layers.len() == self.stack.layers.len()
            && stack.substrate == self.stack.substrate;
        let deepest = stack
            .layers
            .iter()
            .zip(&self.stack.layers)
            .rposition(|(a, b)| a != b);
        // The nodes' faces are in the varied layer's units and on its K_u, K_d: kept only while
        // its material is.
        let same_face = related
            && stack.layers[self.varied].material == self.stack.layers[self.varied].material;
        match deepest {
            Some(v) if same_face && v <= self.varied => {}
            _ => {
                self.varied = match deepest {
                    Some(v) if related => v,
                    _ => 0,
                };
                self.clear_nodes();
            }
        }
        self.stack = stack.clone();
        self.s_far = stack.s_far();
        self.generation += 1;
    }

    /// S of the stack served at wavenumber q ≥ 0 (1/m): the value of [`Stack::response_into`].
    pub fn s(&mut self, q: f64) -> f64 {
        let i = self.node::<false>(q);
        self.s[i].s
    }

    /// S⁻² of the stack served at the wavenumbers `q` (the values of [`StackCache::s`]), into
    /// `out`. The loop with the kernels inlined is compiled also for AVX2 (as `compute_s`).
    pub fn k_many(&mut self, q: &[f64], out: &mut [f64]) {
        with_avx2!(self.k_many_avx2(q, out), self.k_many_in(q, out))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn k_many_avx2(&mut self, q: &[f64], out: &mut [f64]) {
        self.k_many_in(q, out);
    }

    #[inline(always)]
    fn k_many_in(&mut self, q: &[f64], out: &mut [f64]) {
        for (o, &q) in out.iter_mut().zip(q) {
            let i = self.node::<true>(q);
            *o = self.s[i].s.powi(-2);
        }
    }

    /// f_k², g_k² at the interface `k` of the stack served at the wavenumbers `q` (the values of
    /// [`StackCache::response`]), into `f2` and `g2`. The loop with S's kernels inlined is
    /// compiled also for AVX2 (as `compute_s`).
    pub fn interface_many(&mut self, k: usize, q: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        with_avx2!(
            self.interface_many_avx2(k, q, f2, g2),
            self.interface_many_in(k, q, f2, g2)
        )
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn interface_many_avx2(&mut self, k: usize, q: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        self.interface_many_in(k, q, f2, g2);
    }

    #[inline(always)]
    fn interface_many_in(&mut self, k: usize, q: &[f64], f2: &mut [f64], g2: &mut [f64]) {
        let n = self.stack.layers.len();
        for ((fo, go), &q) in f2.iter_mut().zip(g2.iter_mut()).zip(q) {
            let i = self.node::<true>(q);
            if self.fg_generation[i] != self.generation {
                self.compute_interfaces(i);
            }
            let (f, g) = self.interfaces[i * n + k];
            (*fo, *go) = (f * f, g * g);
        }
    }

    /// S and every (f_k, g_k) of the stack served at wavenumber q ≥ 0 (1/m): the values of
    /// [`Stack::response_into`].
    pub fn response(&mut self, q: f64) -> (f64, &[(f64, f64)]) {
        let i = self.node::<false>(q);
        if self.fg_generation[i] != self.generation {
            self.compute_interfaces(i);
        }
        let n = self.stack.layers.len();
        (self.s[i].s, &self.interfaces[i * n..(i + 1) * n])
    }

    /// The index of the node at q, kept if new, with S of the stack served computed if not yet
    /// in this generation. The nodes come mostly in the order kept and computed: the rest is
    /// out of line, S's kernels too unless `INLINE` (for the loops compiled twice, which are
    /// then the kernels' build).
    #[inline(always)]
    fn node<const INLINE: bool>(&mut self, q: f64) -> usize {
        let bits = q.to_bits();
        let i = match self.keys.get(self.cursor + 1) {
            Some(&k) if k == bits => self.cursor + 1,
            _ => self.find_or_add(q),
        };
        self.cursor = i;
        if self.s[i].generation != self.generation {
            if INLINE {
                self.compute_s_in(i, q);
            } else {
                self.compute_s(i, q);
            }
        }
        i
    }

    /// The index of the node at q, kept if new (its base formed when first needed).
    #[inline(never)]
    fn find_or_add(&mut self, q: f64) -> usize {
        let next = self.keys.len();
        let bits = q.to_bits();
        let i = *self.index.entry(bits).or_insert(next as u32) as usize;
        if i == next {
            let n = self.stack.layers.len();
            let below = n - self.varied - 1;
            self.keys.push(bits);
            self.s.push(NodeS {
                generation: 0,
                s: 0.0,
            });
            self.fg_generation.push(0);
            self.faces.push(None);
            self.base_steps
                .resize(self.base_steps.len() + below, EMPTY_STEP);
            self.interfaces
                .resize(self.interfaces.len() + n, (0.0, 0.0));
        }
        i
    }

    /// S of the stack served at node `i` (wavenumber q): the top layer's half-space's where
    /// q·d_1 > [`X_FAR`] ([`Stack::s_far`]: the same value to the last bit), else from its steps
    /// above the base, with the interface kernels where q·d_1 ≤ [`X_EAGER`]. Like
    /// [`Self::compute_interfaces`], compiled also for AVX2 and run so where the CPU has it
    /// (`crate::simd`: everything below is inlined into both builds; the same operations, so the
    /// same values as [`Stack::response_into`]'s baseline build to the last bit).
    #[inline(never)]
    fn compute_s(&mut self, i: usize, q: f64) {
        with_avx2!(self.compute_s_avx2(i, q), self.compute_s_in(i, q))
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn compute_s_avx2(&mut self, i: usize, q: f64) {
        self.compute_s_in(i, q);
    }

    #[inline(always)]
    fn compute_s_in(&mut self, i: usize, q: f64) {
        let x = q * self.stack.layers[0].thickness;
        let s = if x > X_FAR {
            self.s_far
        } else {
            let u0 = self.compute_steps(i, q);
            if x <= X_EAGER {
                self.interfaces_at(i, u0);
            }
            self.stack.s_of(u0)
        };
        self.s[i] = NodeS {
            generation: self.generation,
            s,
        };
    }

    /// The steps above the base of the stack served at node `i` (wavenumber q) into `upper`
    /// (the base formed first if it is not yet), and the top displacement ũ(0) under
    /// t(0) = (0, 1), in the top layer's units: where the downward pass starts.
    #[inline(always)]
    fn compute_steps(&mut self, i: usize, q: f64) -> V2 {
        let (n, above) = (self.stack.layers.len(), self.varied + 1);
        let below = n - above;
        let face = match &self.faces[i] {
            Some(face) => face,
            None => {
                let sub = self.stack.substrate_stiffness();
                let steps = &mut self.base_steps[i * below..(i + 1) * below];
                let base_k = self.stack.up(q, above, sub, steps);
                let c = &self.stack.consts[self.varied];
                self.faces[i].insert(Face::new(c, scale(&base_k, c.inv_two_g)))
            }
        };
        let upper = &mut self.upper[..above];
        self.stack.up_from_face(q, face, upper);
        self.stack.top_displacement(&upper[0], [0.0, 1.0])
    }

    /// Every (f_k, g_k) of the stack served at node `i` from the top displacement `u0` and the
    /// steps above the base just formed ([`Self::compute_steps`]): the downward pass.
    #[inline(always)]
    fn interfaces_at(&mut self, i: usize, u0: V2) {
        let n = self.stack.layers.len();
        let (above, below) = (self.varied + 1, n - self.varied - 1);
        let lower = &self.base_steps[i * below..(i + 1) * below];
        let interfaces = &mut self.interfaces[i * n..(i + 1) * n];
        self.stack
            .interfaces_from(u0, &self.upper[..above], lower, interfaces);
        self.fg_generation[i] = self.generation;
    }

    /// Every (f_k, g_k) of the stack served at node `i`, whose S is computed but not its
    /// interface kernels (q·d_1 > [`X_EAGER`]): the steps above the base formed again, then the
    /// downward pass.
    #[inline(never)]
    fn compute_interfaces(&mut self, i: usize) {
        with_avx2!(
            self.compute_interfaces_avx2(i),
            self.compute_interfaces_in(i)
        )
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn compute_interfaces_avx2(&mut self, i: usize) {
        self.compute_interfaces_in(i);
    }

    #[inline(always)]
    fn compute_interfaces_in(&mut self, i: usize) {
        let u0 = self.compute_steps(i, f64::from_bits(self.keys[i]));
        self.interfaces_at(i, u0);
    }
}

/// A placeholder step, overwritten before it is read.
const EMPTY_STEP: Step = Step::Thick {
    kb: I2,
    v_of_t: I2,
    b: I2,
    i_er: I2,
};

#[inline(always)]
fn scale_v(v: V2, s: f64) -> V2 {
    [v[0] * s, v[1] * s]
}

/// The thin-layer step with the propagator Q = exp(−xA) on the stiffness K̃_b below the layer,
/// into `step` (written in place: a step is some hundred bytes); X and Y (K̃_t = X Y⁻¹).
#[inline(always)]
fn thin_step(c: &Consts, x: f64, kb: M2, step: &mut Step) -> (M2, M2) {
    let (p, [quu, qut, qtu, qtt]) = c.propagators_minus_i(x);
    let x_m = add(&add(&qtu, &kb), &mul(&qtt, &kb));
    let y_m = add(&add(&I2, &quu), &mul(&qut, &kb));
    *step = Step::Thin {
        kb,
        x_inv: inv(&x_m),
        y: y_m,
        p,
    };
    (x_m, y_m)
}

/// [`thin_step`] and the stiffness K̃_t above the layer.
#[inline(always)]
fn thin_up(c: &Consts, x: f64, kb: M2, step: &mut Step) -> M2 {
    let (x_m, y_m) = thin_step(c, x, kb, step);
    mul_sym(&x_m, &inv(&y_m))
}

/// What a layer's thick step needs of the stiffness K̃_b below it (in the layer's units), none
/// of it depending on the layer's thickness: K̃_b, (K_u − K̃_b)⁻¹(K̃_b − K_d) and
/// (K_u − K_d)(K_u − K̃_b)⁻¹.
#[derive(Debug, Clone, Copy)]
struct Face {
    kb: M2,
    r0: M2,
    b0: M2,
}

impl Face {
    /// The face of layer `c` on the stiffness K̃_b (in its units) below it.
    #[inline(always)]
    fn new(c: &Consts, kb: M2) -> Self {
        let ku_kb_inv = inv(&sub(&c.ku, &kb));
        Self {
            kb,
            r0: mul(&ku_kb_inv, &sub(&kb, &c.kd)),
            b0: scale(&ku_kb_inv, c.ku_minus_kd()),
        }
    }
}

/// The thick-layer step with decaying exponentials only, into `step`; ER.
#[inline(always)]
fn thick_step(c: &Consts, x: f64, face: &Face, step: &mut Step) -> M2 {
    let e = (-x).exp();
    let xk = x / c.kappa;
    let ed = scale(&[[1.0 - xk, xk], [-xk, 1.0 + xk]], e);
    let eu = scale(&[[1.0 - xk, -xk], [xk, 1.0 + xk]], e);
    // R = (K_u − K̃_b)⁻¹(K̃_b − K_d) E_d, B = (K_u − K̃_b)⁻¹(K_u − K_d) E_d.
    let er = mul(&eu, &mul(&face.r0, &ed));
    *step = Step::Thick {
        kb: face.kb,
        // K̃_t (I + ER) = K_d (I + ER) + (K_u − K_d) ER.
        v_of_t: inv(&add(&c.kd, &mul(&c.ku, &er))),
        b: mul(&face.b0, &ed),
        i_er: add(&I2, &er),
    };
    er
}

/// [`thick_step`] and the stiffness K̃_t above the layer.
#[inline(always)]
fn thick_up(c: &Consts, x: f64, face: &Face, step: &mut Step) -> M2 {
    let er = thick_step(c, x, face, step);
    let i_er = add(&I2, &er);
    add(&c.kd, &mul_sym(&scale(&er, c.ku_minus_kd()), &inv(&i_er)))
}

/// The state (ũ_b, t_b) at a layer's bottom from (ũ_t, t_t) at its top.
#[inline(always)]
fn down(step: &Step, ut: V2, t: V2) -> (V2, V2) {
    match step {
        Step::Thick { kb, v_of_t, b, .. } => {
            let ub = mulv(b, mulv(v_of_t, t));
            (ub, mulv(kb, ub))
        }
        Step::Thin { kb, x_inv, p, .. } => {
            let [puu, put, ptu, ptt] = p;
            let zero = [0.0, 0.0];
            let ub_solve = mulv_add_terms(x_inv, t, zero);
            let (fwd, fwd_terms) = mulv_add_terms(puu, ut, ut);
            let (fwd2, fwd2_terms) = mulv_add_terms(put, t, zero);
            let ub_fwd = (
                [fwd[0] + fwd2[0], fwd[1] + fwd2[1]],
                [fwd_terms[0] + fwd2_terms[0], fwd_terms[1] + fwd2_terms[1]],
            );
            let ub = pick(ub_solve, ub_fwd);
            let tb_stiff = mulv_add_terms(kb, ub, zero);
            let (d1, d1_terms) = mulv_add_terms(ptu, ut, t);
            let (d2, d2_terms) = mulv_add_terms(ptt, t, zero);
            let tb_fwd = (
                [d1[0] + d2[0], d1[1] + d2[1]],
                [d1_terms[0] + d2_terms[0], d1_terms[1] + d2_terms[1]],
            );
            (ub, pick(tb_stiff, tb_fwd))
        }
    }
}
