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
//! Stresses. From the top, t(0) = (0, 1) and ũ(0) = K̃_1⁻¹ t(0), or Y X⁻¹ t(0) if layer 1 is thin
//! (S = −W̃(0)/(2(1 − ν_1))); down
//! through each layer, given the state (ũ_t, t_t) at its top:
//! - thick: v = (K̃_t (I + ER))⁻¹ t_t, ũ_b = B v, t_b = K̃_b ũ_b;
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

use super::Elastic;
use crate::error::Error;
use serde::Serialize;

/// Relative error bound of [`Stack::response`]'s S, f_k and g_k where their magnitude is at
/// least 1e−30, as asserted by the test against the high-precision reference (measured worst:
/// 4e−13).
pub const STACK_RTOL: f64 = 1e-11;

/// The most layers a stack may have (the range the accuracy is tested on).
pub const MAX_LAYERS: usize = 10;

/// Above this q·d a layer is "thick" (decaying-exponential step), at or below "thin" (series).
const X_THIN: f64 = 1.0;

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

const ALPHA_M1: [f64; TERMS] = series(4, true, false);
const BETA_MX: [f64; TERMS] = series(5, true, false);
const GAMMA: [f64; TERMS] = series(1, false, true);
const DELTA: [f64; TERMS] = series(3, true, false);

fn horner(c: &[f64; TERMS], x2: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &ck| acc * x2 + ck)
}

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

fn mulv(a: &M2, v: V2) -> V2 {
    [
        a[0][0] * v[0] + a[0][1] * v[1],
        a[1][0] * v[0] + a[1][1] * v[1],
    ]
}

fn add(a: &M2, b: &M2) -> M2 {
    [
        [a[0][0] + b[0][0], a[0][1] + b[0][1]],
        [a[1][0] + b[1][0], a[1][1] + b[1][1]],
    ]
}

fn sub(a: &M2, b: &M2) -> M2 {
    [
        [a[0][0] - b[0][0], a[0][1] - b[0][1]],
        [a[1][0] - b[1][0], a[1][1] - b[1][1]],
    ]
}

fn scale(a: &M2, s: f64) -> M2 {
    [[a[0][0] * s, a[0][1] * s], [a[1][0] * s, a[1][1] * s]]
}

fn inv(a: &M2) -> M2 {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    [
        [a[1][1] / det, -a[0][1] / det],
        [-a[1][0] / det, a[0][0] / det],
    ]
}

const I2: M2 = [[1.0, 0.0], [0.0, 1.0]];

/// Σ|terms| / |sum|: how many times the rounding of the terms is magnified in their sum
/// (1 for an exact zero of zero terms).
fn ratio(terms: f64, sum: f64) -> f64 {
    if sum != 0.0 {
        terms / sum.abs()
    } else if terms == 0.0 {
        1.0
    } else {
        f64::INFINITY
    }
}

/// The product a·b of a symmetric result: both off-diagonal entries from whichever of the two
/// computed ones cancels less.
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
        Self {
            two_g: 2.0 * m.shear_modulus(),
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

    /// exp(±xA) − I for 0 ≤ x ≤ 1 (sign +1 for P, −1 for Q).
    fn propagator_minus_i(&self, x: f64, sign: f64) -> M4 {
        let x2 = x * x;
        let am1 = -x2 * x2 * horner(&ALPHA_M1, x2);
        let beta = sign * (x - x2 * x2 * x * horner(&BETA_MX, x2));
        let gamma = x2 * horner(&GAMMA, x2);
        let delta = sign * x2 * x * horner(&DELTA, x2);
        let [a1, a2, a3] = &self.powers;
        let mut m = [[0.0; 4]; 4];
        for (i, mi) in m.iter_mut().enumerate() {
            for (j, mij) in mi.iter_mut().enumerate() {
                let diag = if i == j { am1 } else { 0.0 };
                *mij = diag + beta * a1[i][j] + gamma * a2[i][j] + delta * a3[i][j];
            }
        }
        m
    }
}

/// What the downward pass needs of one layer, in that layer's units.
#[derive(Debug, Clone, Copy)]
enum Step {
    Thin {
        kb: M2,
        x_inv: M2,
        y: M2,
        /// exp(xA) − I.
        p: M4,
    },
    Thick {
        kb: M2,
        /// (K̃_t (I + ER))⁻¹: top traction to the downward part's displacement.
        v_of_t: M2,
        b: M2,
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
        let mut steps = [Step::Thin {
            kb: I2,
            x_inv: I2,
            y: I2,
            p: [[0.0; 4]; 4],
        }; MAX_LAYERS];
        let sub = &self.sub_consts;
        let mut k_pa = scale(&sub.kd, sub.two_g);
        for (i, (layer, c)) in self.layers.iter().zip(&self.consts).enumerate().rev() {
            let kb = scale(&k_pa, 1.0 / c.two_g);
            let x = q * layer.thickness;
            let (kt, step) = if x <= X_THIN {
                thin_up(c, x, kb)
            } else {
                thick_up(c, x, kb)
            };
            steps[i] = step;
            k_pa = scale(&kt, c.two_g);
        }
        let top = &self.consts[0];
        let mut t = [0.0, 1.0];
        // The top compliance: Y X⁻¹ for a thin top layer (no inversion of the stiffness, which
        // cancels for a thin incompressible layer on a far stiffer base), K̃_1⁻¹ otherwise.
        let u0 = match &steps[0] {
            Step::Thin { x_inv, y, .. } => mulv(y, mulv(x_inv, t)),
            Step::Thick { .. } => mulv(&inv(&scale(&k_pa, 1.0 / top.two_g)), t),
        };
        let s = -u0[1] / (2.0 * (1.0 - self.layers[0].material.poisson));
        // Displacement times q (dimensionless): layer k's ũ is 2G_k times this.
        let mut uq = scale_v(u0, 1.0 / top.two_g);
        for ((step, c), o) in steps.iter().zip(&self.consts).zip(out.iter_mut()) {
            let ut = scale_v(uq, c.two_g);
            let (ub, tb) = down(step, ut, t);
            *o = (tb[1], tb[0]);
            t = tb;
            uq = scale_v(ub, 1.0 / c.two_g);
        }
        s
    }
}

fn scale_v(v: V2, s: f64) -> V2 {
    [v[0] * s, v[1] * s]
}

/// The thin-layer step: K̃_t from K̃_b with the propagator Q = exp(−xA).
fn thin_up(c: &Consts, x: f64, kb: M2) -> (M2, Step) {
    let [quu, qut, qtu, qtt] = blocks(&c.propagator_minus_i(x, -1.0));
    let x_m = add(&add(&qtu, &kb), &mul(&qtt, &kb));
    let y_m = add(&add(&I2, &quu), &mul(&qut, &kb));
    let kt = mul_sym(&x_m, &inv(&y_m));
    let step = Step::Thin {
        kb,
        x_inv: inv(&x_m),
        y: y_m,
        p: c.propagator_minus_i(x, 1.0),
    };
    (kt, step)
}

/// The thick-layer step: K̃_t from K̃_b with decaying exponentials only.
fn thick_up(c: &Consts, x: f64, kb: M2) -> (M2, Step) {
    let e = (-x).exp();
    let xk = x / c.kappa;
    let ed = scale(&[[1.0 - xk, xk], [-xk, 1.0 + xk]], e);
    let eu = scale(&[[1.0 - xk, -xk], [xk, 1.0 + xk]], e);
    let ku_kb_inv = inv(&sub(&c.ku, &kb));
    let r = mul(&ku_kb_inv, &mul(&sub(&kb, &c.kd), &ed));
    let er = mul(&eu, &r);
    let i_er = add(&I2, &er);
    let kt = add(&c.kd, &mul_sym(&scale(&er, c.ku_minus_kd()), &inv(&i_er)));
    let step = Step::Thick {
        kb,
        v_of_t: inv(&mul(&kt, &i_er)),
        b: scale(&mul(&ku_kb_inv, &ed), c.ku_minus_kd()),
    };
    (kt, step)
}

/// The state (ũ_b, t_b) at a layer's bottom from (ũ_t, t_t) at its top.
fn down(step: &Step, ut: V2, t: V2) -> (V2, V2) {
    match step {
        Step::Thick { kb, v_of_t, b } => {
            let ub = mulv(b, mulv(v_of_t, t));
            (ub, mulv(kb, ub))
        }
        Step::Thin { kb, x_inv, p, .. } => {
            let [puu, put, ptu, ptt] = blocks(p);
            let zero = [0.0, 0.0];
            let ub_solve = mulv_add_terms(x_inv, t, zero);
            let (fwd, fwd_terms) = mulv_add_terms(&puu, ut, ut);
            let (fwd2, fwd2_terms) = mulv_add_terms(&put, t, zero);
            let ub_fwd = (
                [fwd[0] + fwd2[0], fwd[1] + fwd2[1]],
                [fwd_terms[0] + fwd2_terms[0], fwd_terms[1] + fwd2_terms[1]],
            );
            let ub = pick(ub_solve, ub_fwd);
            let tb_stiff = mulv_add_terms(kb, ub, zero);
            let (d1, d1_terms) = mulv_add_terms(&ptu, ut, t);
            let (d2, d2_terms) = mulv_add_terms(&ptt, t, zero);
            let tb_fwd = (
                [d1[0] + d2[0], d1[1] + d2[1]],
                [d1_terms[0] + d2_terms[0], d1_terms[1] + d2_terms[1]],
            );
            (ub, pick(tb_stiff, tb_fwd))
        }
    }
}
