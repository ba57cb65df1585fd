//! erfcx(u) = e^{u²} erfc(u) for 1.25 ≤ u < 28 with one exponential: fdlibm's erfc there is
//! erfc(u) = e^{−u² − 0.5625 + R(s)/S(s)}/u with s = 1/u² and the rational R/S below (FreeBSD
//! msun s_erf.c, as in the `libm` crate), so erfcx(u) = e^{R/S − 0.5625}/u exactly in the same
//! approximation; the −u² that erfc builds in two pieces (to keep the rounding of u² out) and
//! that erfcx takes out again is never formed. The approximation's error is below 2^−57 on
//! each range, and the exponent is about −0.57 to −0.56, so its rounding costs one ulp.
//!
//! Coefficients from s_erf.c, whose notice is kept as asked:
//! Copyright (C) 1993 by Sun Microsystems, Inc. All rights reserved. Developed at SunPro, a Sun
//! Microsystems, Inc. business. Permission to use, copy, modify, and distribute this software is
//! freely granted, provided that this notice is preserved.

/// R/S on [1.25, 1/0.35): numerator (RA0..RA7) and denominator (1, SA1..SA8) in s = 1/u².
const RA: [f64; 8] = [
    -0.009_864_944_034_847_148,
    -0.693_858_572_707_181_8,
    -10.558_626_225_323_291,
    -62.375_332_450_326_006,
    -162.396_669_462_573_47,
    -184.605_092_906_711_04,
    -81.287_435_506_306_6,
    -9.814_329_344_169_145,
];
const SA: [f64; 8] = [
    19.651_271_667_439_257,
    137.657_754_143_519_04,
    434.565_877_475_229_23,
    645.387_271_733_267_9,
    429.008_140_027_567_83,
    108.635_005_541_779_44,
    6.570_249_770_319_282,
    -0.060_424_415_214_858_1,
];
/// R/S on [1/0.35, 28): RB0..RB6 and (1, SB1..SB7), each with a zero appended so that both
/// ranges run one Horner loop of eight steps (a leading zero coefficient leaves Horner's rule
/// exact: its first step gives 0 + s·0 = 0).
const RB: [f64; 8] = [
    -0.009_864_942_924_700_1,
    -0.799_283_237_680_523,
    -17.757_954_917_754_752,
    -160.636_384_855_821_92,
    -637.566_443_368_389_6,
    -1_025.095_131_611_077_2,
    -483.519_191_608_651_4,
    0.0,
];
const SB: [f64; 8] = [
    30.338_060_743_482_46,
    325.792_512_996_573_9,
    1_536.729_586_084_437,
    3_199.858_219_508_595_5,
    2_553.050_406_433_164_4,
    474.528_541_206_955_37,
    -22.440_952_446_585_82,
    0.0,
];

/// The high word of 1/0.35 in fdlibm's range test (the ranges split exactly where its erfc's
/// do).
const SPLIT_HIGH_WORD: u64 = 0x4006_db6d;

/// erfcx(u) for 1.25 ≤ u < 28 (the caller keeps to that range).
pub(super) fn erfcx_far(u: f64) -> f64 {
    debug_assert!((1.25..28.0).contains(&u));
    exponent(u).exp() / u
}

/// The exponent R/S − 0.5625 of erfcx(u) = e^{R/S − 0.5625}/u, with no branch (the range's
/// coefficients are selected per step, so that a loop over many u is vectorised): R and
/// S − 1 by Horner's rule in s = 1/u², in the order fdlibm evaluates them.
#[inline(always)]
pub(super) fn exponent(u: f64) -> f64 {
    let s = 1.0 / (u * u);
    let near = u.to_bits() >> 32 < SPLIT_HIGH_WORD;
    let (mut r, mut q) = (0.0, 0.0);
    for j in (0..8).rev() {
        let (rc, qc) = if near { (RA[j], SA[j]) } else { (RB[j], SB[j]) };
        r = rc + s * r;
        q = qc + s * q;
    }
    r / (1.0 + s * q) - 0.5625
}
