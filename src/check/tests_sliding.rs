//! Tests of the premises of the minimum-thickness search under sliding (module docs of
//! [`super::min_thickness`], "Under sliding"): the friction kernels' shapes in q·d over the
//! material range, and the peaks' monotonicity and spread.

use super::min_thickness::wide_threshold;
use super::*;
use crate::contact::NormalStress;
use crate::layer::{Bilayer, Elastic};
use crate::tail::{ShearVector, anisotropy_spread, one_step_shortfall};

/// Points per decade of q·d in the kernel scans.
const PER_DECADE: f64 = 100.0;

/// The material pairs of the scans: substrate/film modulus ratios 1e-8 … 1e8 (every decade),
/// Poisson ratios 0, 0.25, 0.5 on both sides.
fn pairs() -> Vec<Bilayer> {
    let e = |y: f64, nu: f64| Elastic::new(y, nu).unwrap();
    let mut out = Vec::new();
    for k in -8..=8 {
        for nu0 in [0.0, 0.25, 0.5] {
            for nu1 in [0.0, 0.25, 0.5] {
                out.push(Bilayer::new(e(1e6, nu0), e(1e6 * 10f64.powi(k), nu1)));
            }
        }
    }
    out
}

/// ln(q·d) from 1e-8 to 1e4 at [`PER_DECADE`].
fn grid() -> Vec<f64> {
    let n = (12.0 * PER_DECADE) as usize;
    (0..=n)
        .map(|i| (1e-8f64).ln() + i as f64 * std::f64::consts::LN_10 / PER_DECADE)
        .collect()
}

/// ln of the friction kernels at x = q·d from their undecayed forms (finite at every x):
/// ln √(((g_t + h)/2)² + (g_t − h)²/8) (the x-shear per unit μ) and ln f_t.
fn ln_friction(b: &Bilayer, x: f64) -> (f64, f64) {
    let s = b.shear_undecayed(x);
    let half_sum = s.h + 0.5 * s.diff;
    let kx = (half_sum * half_sum + s.diff * s.diff / 8.0).sqrt();
    (kx.ln() - x, s.f_t.ln() - x)
}

/// The smallest ratio, over every window of the grid at most `n` points long, of the larger
/// value at its ends to the largest inside it (in ln: the difference), for a kernel given by
/// its ln on the grid: how far a kernel can rise between the ends of a step of that length.
fn worst_end_ratio(ln_k: &[f64], n: usize) -> f64 {
    let mut worst = f64::INFINITY;
    for i in 0..ln_k.len() {
        let mut inside = f64::NEG_INFINITY;
        for j in i + 1..(i + n + 1).min(ln_k.len()) {
            worst = worst.min(ln_k[i].max(ln_k[j]) - inside);
            inside = inside.max(ln_k[j]);
        }
    }
    worst.exp()
}

/// The premise of the widened steps under sliding (module docs, step 2 and "Under sliding"):
/// over q·d from 1e-8 to 1e4 and every pair, a step of at most a widened step's length sees at
/// one end at least the step's `level` of the largest value inside, for |g| (up to q·d = 700,
/// where it is still in f64's normal range; beyond, every kernel decays as (a + b x)e^{−x}), for
/// the friction x-shear kernel √(((g_t + h)/2)² + (g_t − h)²/8) and for f_t. Also step 1's
/// premise for the friction kernels: they only fall beyond the scan start q·d = 10.
#[test]
fn friction_kernels_rise_between_step_ends_no_more_than_the_shear_kernel() {
    let t = grid();
    let start = t
        .iter()
        .position(|&x| x.exp() >= SCAN_START_QD * (1.0 - 1e-12))
        .unwrap();
    let g_end = t.iter().position(|&x| x.exp() > 700.0).unwrap();
    // The worst end ratio of each kernel (|g|, x-shear, f_t) for each widened step.
    let mut worst = [[f64::INFINITY; WIDE_STEPS.len()]; 3];
    for b in pairs() {
        let ln_g: Vec<f64> = t[..g_end]
            .iter()
            .map(|&x| b.response(x.exp()).g.abs().ln())
            .collect();
        let (ln_kx, ln_ft): (Vec<f64>, Vec<f64>) =
            t.iter().map(|&x| ln_friction(&b, x.exp())).unzip();
        for k in [&ln_kx, &ln_ft] {
            assert!(k.iter().all(|v| v.is_finite()), "{b:?}");
            assert!(
                k[start..].windows(2).all(|w| w[1] <= w[0] + 1e-13),
                "{b:?} rises beyond q d = 10"
            );
        }
        for (i, w) in WIDE_STEPS.iter().enumerate() {
            let n = (w.decades * PER_DECADE).round() as usize;
            for (j, k) in [&ln_g, &ln_kx, &ln_ft].into_iter().enumerate() {
                worst[j][i] = worst[j][i].min(worst_end_ratio(k, n));
            }
        }
    }
    for (i, w) in WIDE_STEPS.iter().enumerate() {
        for (j, name) in ["|g|", "x-shear", "f_t"].into_iter().enumerate() {
            assert!(
                worst[j][i] >= w.level,
                "{name} over {} decades: {} < {}",
                w.decades,
                worst[j][i],
                w.level
            );
        }
    }
    eprintln!("worst end ratios (|g|, x-shear, f_t) per widened step: {worst:?}");
}

/// The vector peak's properties the search uses (module docs, "Under sliding"): nondecreasing
/// in the x rms at any y rms (step 1; proven for the y rms and the mean). And how far one
/// Newton step ([`ShearVector::peak_from`], the search's read) lands below the peak τ* from any
/// start L between τ* and its upper bound τ_hi (where it clips the start): at most
/// [`one_step_shortfall`] of τ*. Both are homogeneous of degree 1 in (m, sx, sy, L), so the
/// grid over m/sx, sy/sx ≤ 1 (the search has sy ≤ sx) and (L − τ*)/(τ_hi − τ*) covers every
/// scene; printed per ε with the worst case's parameters and the bound's margin, and the worst
/// from starts within 1e−5 of τ* (the thick-film slack's comparison, module docs).
#[test]
fn one_step_peaks_fall_short_of_the_peak_by_at_most_the_bound() {
    let ratios = [0.0, 0.1, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];
    let mut means = vec![0.0];
    means.extend((0..=12).map(|i| 10f64.powf(-3.0 + i as f64 / 2.0)));
    means.extend([0.178, 0.316, 0.562]);
    for eps in [
        1e-300f64, 1e-30, 1e-6, 1e-3, 1e-2, 0.05, 0.1, 0.2, 0.3, 0.4, 0.45, 0.49,
    ] {
        let phi = (-2.0 * eps.ln()).sqrt();
        let (mut worst, mut at, mut near) = (0.0f64, (0.0, 0.0, 0.0), 0.0f64);
        for &m in &means {
            let mut last = 0.0;
            for &r in &ratios {
                let v = ShearVector::new(m, 1.0, r).unwrap();
                let peak = v.peak(eps).unwrap();
                assert!(
                    peak.value >= last * (1.0 - 1e-12),
                    "eps {eps} m {m} sy/sx {r}: {} < {last}",
                    peak.value
                );
                last = peak.value;
                let hi = m + phi;
                let short = |level: f64| {
                    let r1 = v.peak_from(level, eps).unwrap();
                    1.0 - (r1.value + r1.err + peak.err) / peak.value
                };
                for k in 0..=16 {
                    let t = (k as f64 / 16.0).powi(2);
                    let s = short(peak.value + t * (hi - peak.value));
                    if s > worst {
                        (worst, at) = (s, (m, r, t));
                    }
                }
                near = near.max(short(peak.value * (1.0 + 1e-5)));
            }
        }
        let bound = one_step_shortfall(eps);
        eprintln!(
            "eps {eps:e}: one step lands at most {worst:.2e} below the peak (m/sx {}, sy/sx \
             {}, start fraction {:.3}), {:.2} of the bound; from within 1e-5 of it {near:.1e}",
            at.0,
            at.1,
            at.2,
            worst / bound
        );
        assert!(worst <= bound, "eps {eps}: {worst:e} > {bound:e}");
        assert!(near <= 1e-10, "eps {eps}: {near:e}");
    }
}

/// The spread the search allows for (`tail::anisotropy_spread`): over the mean m ≥ 0, the peak
/// of (m + X, Y) with equal rms exceeds the folded normal's (Y = 0) by at most the spread, the
/// value at m = 0.
#[test]
fn isotropic_peak_exceeds_the_folded_one_by_at_most_the_spread() {
    for eps in [
        1e-300, 1e-100, 1e-30, 1e-12, 1e-6, 1e-3, 1e-2, 0.1, 0.3, 0.49,
    ] {
        let spread = anisotropy_spread(eps);
        let ratio = |m: f64| {
            let iso = ShearVector::new(m, 1.0, 1.0).unwrap().peak(eps).unwrap();
            let fold = ShearVector::new(m, 1.0, 0.0).unwrap().peak(eps).unwrap();
            iso.value / fold.value
        };
        assert!((ratio(0.0) / spread - 1.0).abs() < 1e-10, "{eps}");
        for i in 0..=60 {
            let m = 10f64.powf(-3.0 + i as f64 / 10.0);
            assert!(ratio(m) <= spread * (1.0 + 1e-10), "eps {eps} m {m}");
        }
    }
}

/// The interface normal stress's peak (Persson's form centred at p0, width σ) shrinks with σ
/// no faster than σ: peak(p0, λσ) ≥ λ peak(p0, σ) for 0 < λ ≤ 1, so the friction-driven part
/// of σ_rms carries the widened steps' argument like the shear does.
#[test]
fn normal_stress_peak_falls_no_faster_than_its_width() {
    for eps in [1e-12, 1e-6, 1e-2, 0.3] {
        for i in 0..=30 {
            let p0 = 10f64.powf(-3.0 + i as f64 / 5.0);
            let peak = |s: f64| NormalStress { p0, sigma_rms: s }.peak(eps).value;
            let full = peak(1.0);
            for lambda in [1e-3, 0.1, 0.25, 0.5, 0.9, 0.999] {
                assert!(
                    peak(lambda) >= lambda * full * (1.0 - 1e-12),
                    "eps {eps} p0 {p0} lambda {lambda}"
                );
            }
        }
    }
}

/// The widened steps' thresholds hold the argument's bound: below level/(√2·spread) for every
/// exceedance the vector peak takes under friction, and unchanged without it (the half-normal
/// rule's bound, level/√2). With the thresholds as they were (0.15 and 0.3 whatever the
/// spread) this fails from ε = 0.0101 on, where the spread passes 0.25/(√2·0.15) = 1.1785.
#[test]
fn wide_thresholds_stay_below_the_bound_at_every_exceedance() {
    for w in WIDE_STEPS {
        assert_eq!(wide_threshold(&w, 1.0), w.below);
        for i in 1..=600 {
            let eps = 0.5 * 10f64.powf(-300.0 * (i as f64 / 600.0).powi(3));
            let spread = anisotropy_spread(eps);
            assert!(spread >= 1.0, "{eps}");
            let t = wide_threshold(&w, spread);
            let bound = w.level / (2f64.sqrt() * spread);
            assert!(t <= bound * (1.0 + 1e-15), "{w:?} eps {eps}");
            assert!(t > 0.0);
            if eps <= 0.01 {
                assert_eq!(t, w.below, "eps {eps}");
            }
        }
    }
}

/// The search's reads of the vector peak are exact with respect to its levels (module docs,
/// "Under sliding"): a constructed utilisation at ε = 0.3 (thresholds equal to the argument's
/// bound) whose vector (m, sx, sy) ∝ (0.316, 1, 0.5) (near the largest one-step shortfall,
/// 2.5 %) fails on a band 0.6 wide in ln d, sits at 0.01 above it and at 1.01 of the 0.75-decade
/// step's threshold below it, as the argument allows: a failing point inside the step, an end
/// above the threshold. The first widened step from the scan start ends below the band. Read by
/// one step from the limit alone, that end reads below the threshold, the step is taken and the
/// band is missed (every thickness passes to the floor); read by `read_vector_peak`, the
/// end's peak is solved, the step redone with base steps and d_min found at the band's top.
#[test]
fn one_step_reads_near_a_threshold_are_solved() {
    use super::checker::read_vector_peak;
    use super::min_thickness::{decision_levels, search_min_thickness_spread};
    let eps = 0.3;
    let spread = anisotropy_spread(eps);
    let levels = decision_levels(spread);
    let unit = ShearVector::new(0.316, 1.0, 0.5).unwrap();
    let unit_peak = unit.peak(eps).unwrap().value;
    let (lo, hi) = (1e-9, 1e-2);
    let start = (hi * SCAN_START_QD / BULK_QD).ln();
    let (band_top, band_bottom) = (start - 0.6, start - 1.2);
    let below_band = 1.01 * levels[0];
    // The true utilisation at ln d (limit 1) and the vector that has it as its peak.
    let truth = |x: f64| {
        if x > band_top {
            0.01
        } else if x > band_bottom {
            2.0
        } else {
            below_band
        }
    };
    let vector = |x: f64| {
        let k = truth(x) / unit_peak;
        ShearVector::new(0.316 * k, k, 0.5 * k).unwrap()
    };
    let one_step = vector(band_bottom - 1.0).peak_from(1.0, eps).unwrap().value;
    assert!(one_step < levels[0], "{one_step} >= {}", levels[0]);
    let search = |solve_near_levels: bool| {
        search_min_thickness_spread(lo, hi, spread, 0.0, |d| {
            let v = vector(d.ln());
            let read = if solve_near_levels {
                read_vector_peak(&v, 1.0, eps, &levels)?
            } else {
                v.peak_from(1.0, eps)?
            };
            Ok(Utilisation {
                value: read.value,
                rel_err: 0.0,
                kind: Some(CheckKind::BondShear),
            })
        })
        .unwrap()
    };
    let missed = search(false);
    assert!(missed.all_pass_to_floor, "{missed:?}");
    let found = search(true);
    let d = found.thickness.unwrap().value;
    assert!(!found.all_pass_to_floor);
    assert!(
        (d / band_top.exp() - 1.0).abs() <= D_MIN_RTOL,
        "{d} vs {}",
        band_top.exp()
    );
}

/// The friction floor ([`super::min_thickness`], "The friction floor") only steers the scan's
/// steps: under sliding (μ = 0.5 or 1, the vector rule), on the paper's spectrum with bond
/// strengths that put the floor μp0/limit from 0.02 to 0.4, and on the measured PSD of
/// `examples/measured-rolloff.toml` (floor 0.05), the search with the floor, the one without
/// it and the checker's own all find the crossing that a dense scan of the utilisation from
/// the bulk bound down (40 points per decade, then bisection to 1e-9) finds. The floor never
/// costs evaluations, and on the measured PSD it saves some: there the utilisation stays at
/// the floor for two decades and then turns up steeply, and the plain rule's widened step
/// overshoots its threshold and is redone with base steps.
#[test]
fn the_friction_floor_moves_no_crossing() {
    use super::checker::worst_utilisation;
    use super::min_thickness::search_min_thickness_spread;
    use crate::prec::Settings;
    use crate::psd::Spectrum;
    let paper = Spectrum::self_affine(1.0, 1e5, 1e8, None)
        .unwrap()
        .scaled_to_rms_slope(1.0)
        .unwrap();
    let rubber_on_steel = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(1e11, 0.5).unwrap(),
    );
    let mut cases: Vec<(Spectrum, Design, Settings)> = Vec::new();
    for (mu, floor) in [(0.5, 0.02), (0.5, 0.05), (1.0, 0.1), (0.5, 0.2), (1.0, 0.4)] {
        let p0 = 1e5;
        let design = Design {
            layers: rubber_on_steel,
            pressure: p0,
            yield_strength: Some(2.5e8),
            bond_strength: mu * p0 / floor,
            friction: mu,
            criteria: Criteria {
                shear_tail: Some(ShearTail::Vector),
                epsilon: 1e-6,
                safety_factor: 1.0,
                checks: Checks::all(),
            },
        };
        cases.push((paper.clone(), design, Settings::default()));
    }
    let lib = crate::material::Library::builtin().unwrap();
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/measured-rolloff.toml");
    let scene = crate::scene::Scene::load(Some(&path), &[], &lib).unwrap();
    let mut measured = scene.design();
    measured.friction = 0.5;
    cases.push((
        scene.roughness.spectrum().unwrap().0,
        measured,
        scene.settings,
    ));
    let mut saved = Vec::new();
    for (spectrum, design, settings) in cases {
        let floor = design.friction * design.pressure
            / super::criteria::limit(design.bond_strength, design.criteria.safety_factor);
        let c = Checker::new(&spectrum, design, settings).unwrap();
        let u = |d: f64| worst_utilisation(&c.evaluate(d).unwrap().checks);
        let (lo, hi) = c.scan_range();
        let mut above = hi;
        let fail = (1..)
            .map(|i| hi * 10f64.powf(-i as f64 / 40.0))
            .take_while(|&d| d >= lo)
            .find(|&d| {
                let fails = u(d).value > 1.0;
                if !fails {
                    above = d;
                }
                fails
            })
            .unwrap();
        let (mut a, mut b) = (fail, above);
        while b / a > 1.0 + 1e-9 {
            let mid = (a * b).sqrt();
            if u(mid).value > 1.0 {
                a = mid;
            } else {
                b = mid;
            }
        }
        let spread = anisotropy_spread(c.design().criteria.epsilon);
        let run =
            |floor: f64| search_min_thickness_spread(lo, hi, spread, floor, |d| Ok(u(d))).unwrap();
        let (with, plain) = (run(floor), run(0.0));
        for m in [&with, &plain, &c.min_thickness().unwrap()] {
            let d = m.thickness.unwrap();
            assert!(!m.all_pass_to_floor);
            assert!(
                (d.value - a).abs() <= d.err * 1.0001,
                "floor {floor}: {d:?} vs {a:e}"
            );
        }
        assert!(
            with.evaluations <= plain.evaluations,
            "floor {floor}: {} > {}",
            with.evaluations,
            plain.evaluations
        );
        saved.push(plain.evaluations - with.evaluations);
    }
    assert!(saved[5] >= 2, "{saved:?}");
}
