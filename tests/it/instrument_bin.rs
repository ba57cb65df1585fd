//! Binary instrument readers (Zygo MetroPro, Wyko OPD, Sensofar PLU, Bruker Nanoscope, Keysight
//! MI, Alicona AL3D, FRT) on real files, against the SurfaceTopography library's reading of the
//! same files, and on hostile files (truncated, wrong magic, absurd sizes, corrupted headers).
//!
//! Reference values: SurfaceTopography 1.27.1 (an independent implementation, Python), printed
//! by `python3 tests/data/instrument/st_reference.py tests/data/instrument/FILE` (see its
//! docstring for the environment). Tolerances: pixel sizes 1e-12 relative (the same f32 or
//! text value divided in another order), single heights 1e-12 relative (the same stored count
//! times a scale factor multiplied in another order: a few ulps), rms about the mean 1e-9
//! relative (numpy's pairwise sums against a plain sum over up to 4·10⁵ points).

use coatcheck::Error;
use coatcheck::instrument::{Channel, Reading, al3d, di, frt, metropro, mi, opd, plu};
use std::path::{Path, PathBuf};

type ReadFn = fn(&Path, &[u8]) -> Result<Reading, Error>;
type IsFn = fn(&[u8]) -> bool;

/// The formats: name, sample file, magic test, reader, and the length of the file's prefix the
/// reader needs (every shorter cut must be an error).
const FORMATS: [(&str, &str, IsFn, ReadFn, usize); 7] = [
    (
        "metropro",
        "metropro-1.dat",
        metropro::is_metropro,
        metropro::read_metropro,
        1_844_034,
    ),
    // The last array ("Image") ends at byte 4018408; metadata blocks that are not read follow.
    ("opd", "opd-1.opd", opd::is_opd, opd::read_opd, 4_018_408),
    // One layer of 768 × 576 f32 after the 500-byte header and its 8-byte grid.
    (
        "plu",
        "plu-1.plu",
        plu::is_plu,
        plu::read_plu,
        500 + 8 + 4 * 768 * 576,
    ),
    ("di", "di-1.di", di::is_di, di::read_di, 2_138_112),
    ("mi", "mi-1.mi", mi::is_mi, mi::read_mi, 1_053_649),
    // The depth image (1261 + 4 · 200 · 296); the texture image follows.
    (
        "al3d",
        "al3d-1.al3d",
        al3d::is_al3d,
        al3d::read_al3d,
        238_061,
    ),
    ("frt", "frt-1.frt", frt::is_frt, frt::read_frt, 1_504_364),
];

fn sample(name: &str) -> (PathBuf, Vec<u8>) {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/instrument")
        .join(name);
    let bytes = std::fs::read(&p).unwrap();
    (p, bytes)
}

/// What SurfaceTopography reads for one channel (lengths in m).
struct Ref {
    name: &'static str,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    missing: usize,
    rms: f64,
    /// Heights at (ix, iy); NaN where SurfaceTopography masks the point.
    points: [(usize, usize, f64); 4],
}

fn rel(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a - b).abs() / b.abs() }
}

/// Root mean square about the mean of the measured (non-NaN) points.
fn rms(z: &[f64]) -> f64 {
    let v: Vec<f64> = z.iter().copied().filter(|z| !z.is_nan()).collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
}

fn check(c: &Channel, r: &Ref) {
    assert_eq!(c.name, r.name);
    assert_eq!((c.nx, c.ny), (r.nx, r.ny), "{}", r.name);
    assert_eq!(c.z.len(), c.nx * c.ny);
    assert!(
        rel(c.dx, r.dx) <= 1e-12,
        "{}: dx {} vs {}",
        r.name,
        c.dx,
        r.dx
    );
    assert!(
        rel(c.dy, r.dy) <= 1e-12,
        "{}: dy {} vs {}",
        r.name,
        c.dy,
        r.dy
    );
    let missing = c.z.iter().filter(|z| z.is_nan()).count();
    assert_eq!(missing, r.missing, "{}: non-measured points", r.name);
    assert!(c.z.iter().all(|z| z.is_nan() || z.is_finite()));
    let h = rms(&c.z);
    assert!(
        rel(h, r.rms) <= 1e-9,
        "{}: rms {h:e} vs {:e}",
        r.name,
        r.rms
    );
    for (ix, iy, want) in r.points {
        let got = c.z[iy * c.nx + ix];
        assert!(
            (want.is_nan() && got.is_nan()) || rel(got, want) <= 1e-12,
            "{}: z[{ix}, {iy}] = {got:e}, expected {want:e}",
            r.name
        );
    }
}

fn read(name: &str) -> Reading {
    let (_, file, _, reader, _) = FORMATS.iter().find(|f| f.0 == name).copied().unwrap();
    let (p, bytes) = sample(file);
    reader(&p, &bytes).unwrap()
}

#[test]
fn metropro_reads_as_surface_topography() {
    let r = read("metropro");
    assert_eq!(r.format, "metropro");
    assert_eq!(r.default_channel(), 0);
    let c = &r.channels[0];
    assert!(c.is_height);
    assert_eq!(c.unit_in_file, "m");
    // st_reference.py metropro-1.dat: grid (640, 480), size (0.0007028812979115173,
    // 0.000527160973433638) m, pixel 1.0982520279867458e-06 m, masked 0, rms
    // 7.52882220473459e-08 m; height scale 8.697509726318664e-12 m per count (0.5 · 1 ·
    // 5.7e-7 m / 32768).
    check(
        c,
        &Ref {
            name: "metropro",
            nx: 640,
            ny: 480,
            dx: 1.0982520279867458e-06,
            dy: 1.0982520279867458e-06,
            missing: 0,
            rms: 7.52882220473459e-08,
            points: [
                (0, 0, 5.05753145602552e-05),
                (639, 0, 5.08308995810728e-05),
                (0, 479, 5.056755638157932e-05),
                (320, 160, 5.075044761610435e-05),
            ],
        },
    );
    assert!(rel(0.0007028812979115173 / 640.0, c.dx) <= 1e-12);
    // The one intensity bucket (SurfaceTopography does not read it): 640 × 480 counts.
    assert_eq!(r.channels.len(), 2);
    let i = &r.channels[1];
    assert_eq!(
        (i.name.as_str(), i.nx, i.ny, i.is_height),
        ("intensity", 640, 480, false)
    );
    assert!(
        i.z.iter()
            .all(|&v| (0.0..=65535.0).contains(&v) && v.fract() == 0.0)
    );
}

#[test]
fn opd_reads_as_surface_topography() {
    let r = read("opd");
    assert_eq!(r.format, "opd");
    let names: Vec<&str> = r.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["Raw", "SecArr_0", "Image"]);
    assert_eq!(r.default_channel(), 0);
    let c = &r.channels[0];
    assert!(c.is_height && !r.channels[1].is_height && !r.channels[2].is_height);
    assert_eq!(c.unit_in_file, "nm");
    // st_reference.py opd-1.opd: channel 'Raw', grid (640, 480), size (0.1259091403335333,
    // 0.09443185525014997) mm, pixel 1.9673303177114576e-07 m, masked 116, rms
    // 8.356451162720975e-06 mm; height scale 0.0005772949829101563 mm per unit (λ = 577.29 nm).
    check(
        c,
        &Ref {
            name: "Raw",
            nx: 640,
            ny: 480,
            dx: 1.9673303177114576e-07,
            dy: 1.9673303177114576e-07,
            missing: 116,
            rms: 8.356451162720975e-09,
            points: [
                (0, 0, -2.6550621614908414e-07),
                (639, 0, -2.5646328900066876e-07),
                (0, 479, -2.8399285465906725e-07),
                (320, 160, -2.746491716046585e-07),
            ],
        },
    );
    assert!(rel(0.09443185525014997e-3 / 480.0, c.dy) <= 1e-12);
}

#[test]
fn plu_reads_as_surface_topography() {
    let r = read("plu");
    assert_eq!(r.format, "plu");
    assert_eq!(r.channels.len(), 1);
    let c = &r.channels[0];
    assert!(c.is_height);
    assert_eq!(c.unit_in_file, "µm");
    // st_reference.py plu-1.plu: channel 'layer0', grid (768, 576), size (1274.8800659179688,
    // 956.1600494384766) µm, pixel 1.6600000858306884e-06 m, masked 0, rms
    // 2.834390987634884 µm.
    check(
        c,
        &Ref {
            name: "plu",
            nx: 768,
            ny: 576,
            dx: 1.6600000858306884e-06,
            dy: 1.6600000858306884e-06,
            missing: 0,
            rms: 2.834390987634884e-06,
            points: [
                (0, 0, -0.0001112265625),
                (767, 0, -0.00010144921874999999),
                (0, 575, -0.00011106640625),
                (384, 192, -0.00010626171874999999),
            ],
        },
    );
}

#[test]
fn di_reads_as_surface_topography() {
    let r = read("di");
    assert_eq!(r.format, "di");
    let names: Vec<&str> = r.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["Height", "Height", "Phase", "AmplitudeError"]);
    let heights: Vec<bool> = r.channels.iter().map(|c| c.is_height).collect();
    assert_eq!(heights, [true, true, false, false]);
    assert_eq!(r.default_channel(), 0);
    // st_reference.py di-1.di, channel 0 'Height' (trace): grid (512, 512), size (500, 500)
    // nm, pixel 9.765625000000002e-10 m, masked 0, rms 9.94598680056039 nm; height scale
    // 0.0009249053893746949 nm per count (2.910461 V / 2^16 · 20.82646 nm/V).
    let pixel = 9.765625000000002e-10;
    check(
        &r.channels[0],
        &Ref {
            name: "Height",
            nx: 512,
            ny: 512,
            dx: pixel,
            dy: pixel,
            missing: 0,
            rms: 9.94598680056039e-09,
            points: [
                (0, 0, 6.059980111183002e-09),
                (511, 0, -9.740178655504912e-09),
                (0, 511, 2.8431591669378123e-09),
                (256, 170, -7.861695809684907e-10),
            ],
        },
    );
    // Channel 1 'Height' (retrace): height scale 0.10486797588653565 nm per count, rms
    // 114.01328027385664 nm.
    check(
        &r.channels[1],
        &Ref {
            name: "Height",
            nx: 512,
            ny: 512,
            dx: pixel,
            dy: pixel,
            missing: 0,
            rms: 1.1401328027385664e-07,
            points: [
                (0, 0, -1.3768116554143267e-06),
                (511, 0, -1.3503849254909196e-06),
                (0, 511, -9.934143355731524e-07),
                (256, 170, -1.234191208208638e-06),
            ],
        },
    );
    assert_eq!(r.channels[0].unit_in_file, "nm");
    // Phase and amplitude error: SurfaceTopography gives the raw counts (it scales only
    // heights); here they are in the channel's unit, count · Z scale / 2^16 with the header's
    // `@2:Z scale` of 359.9945 ° and 3999.939 mV and unit soft scales.
    let phase = 359.9945 / 65536.0;
    let amplitude = 3999.939 / 65536.0;
    check(
        &r.channels[2],
        &Ref {
            name: "Phase",
            nx: 512,
            ny: 512,
            dx: pixel,
            dy: pixel,
            missing: 0,
            rms: 683.6853563042765 * phase,
            points: [
                (0, 0, 9174.0 * phase),
                (511, 0, 10356.0 * phase),
                (0, 511, 9878.0 * phase),
                (256, 170, 9953.0 * phase),
            ],
        },
    );
    check(
        &r.channels[3],
        &Ref {
            name: "AmplitudeError",
            nx: 512,
            ny: 512,
            dx: pixel,
            dy: pixel,
            missing: 0,
            rms: 152.65041526098867 * amplitude,
            points: [
                (0, 0, -134.0 * amplitude),
                (511, 0, -65.0 * amplitude),
                (0, 511, 141.0 * amplitude),
                (256, 170, 4.0 * amplitude),
            ],
        },
    );
    assert_eq!(r.channels[3].unit_in_file, "mV");
}

#[test]
fn mi_reads_as_surface_topography() {
    let r = read("mi");
    assert_eq!(r.format, "mi");
    let names: Vec<&str> = r.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["Topography", "Deflection", "Friction", "Friction"]);
    let units: Vec<&str> = r.channels.iter().map(|c| c.unit_in_file.as_str()).collect();
    assert_eq!(units, ["um", "V", "V", "V"]);
    let heights: Vec<bool> = r.channels.iter().map(|c| c.is_height).collect();
    assert_eq!(heights, [true, false, false, false]);
    // st_reference.py mi-1.mi, channel 0 'Topography': grid (256, 256), size (20, 20) µm,
    // pixel 7.812499999999999e-08 m, masked 0, rms 0.033215426493512654 µm; height scale
    // 1.3515818864107133e-09 µm per count (2.9025 µm / 2^31).
    let pixel = 7.812499999999999e-08;
    let topo = Ref {
        name: "Topography",
        nx: 256,
        ny: 256,
        dx: pixel,
        dy: pixel,
        missing: 0,
        rms: 3.321542649351265e-08,
        points: [
            (0, 0, -4.986900329589845e-07),
            (255, 0, -5.981623077392578e-07),
            (0, 255, -5.122423553466797e-07),
            (128, 85, -5.527221679687501e-07),
        ],
    };
    check(&r.channels[0], &topo);
    // Channel 1 'Deflection', in V: height scale 4.6566128730773926e-09 V per count (10 V /
    // 2^31), rms 0.004530321012980325 V.
    let deflection = Ref {
        name: "Deflection",
        rms: 0.004530321012980325,
        points: [
            (0, 0, -0.00244140625),
            (255, 0, -0.00457763671875),
            (0, 255, -0.0030517578125),
            (128, 85, -0.00274658203125),
        ],
        ..topo
    };
    check(&r.channels[1], &deflection);
    // Channels 2 and 3 'Friction' (trace, retrace), V: rms 0.2354761954248449 and
    // 0.23864890741387623 V.
    let friction = Ref {
        name: "Friction",
        rms: 0.2354761954248449,
        points: [
            (0, 0, -0.0738525390625),
            (255, 0, -0.93994140625),
            (0, 255, -0.1165771484375),
            (128, 85, -0.46783447265625),
        ],
        ..deflection
    };
    check(&r.channels[2], &friction);
    let retrace = Ref {
        rms: 0.23864890741387623,
        points: [
            (0, 0, -0.0164794921875),
            (255, 0, -0.90179443359375),
            (0, 255, -0.0714111328125),
            (128, 85, -0.299072265625),
        ],
        ..friction
    };
    check(&r.channels[3], &retrace);
}

#[test]
fn al3d_reads_as_surface_topography() {
    let r = read("al3d");
    assert_eq!(r.format, "al3d");
    assert_eq!(r.channels.len(), 1);
    assert!(r.channels[0].is_height);
    assert_eq!(r.channels[0].unit_in_file, "m");
    // st_reference.py al3d-1.al3d: grid (200, 296), size (8.76054e-05, 0.000129655992) m,
    // pixel 4.38027e-07 m, masked 0 (InvalidPixelValue 3e15 does not occur), rms
    // 7.688265843362921e-06 m.
    check(
        &r.channels[0],
        &Ref {
            name: "al3d",
            nx: 200,
            ny: 296,
            dx: 4.38027e-07,
            dy: 4.38027e-07,
            missing: 0,
            rms: 7.688265843362921e-06,
            points: [
                (0, 0, 0.07635815441608429),
                (199, 0, 0.07634570449590683),
                (0, 295, 0.07633679360151291),
                (100, 98, 0.07634462416172028),
            ],
        },
    );
}

#[test]
fn frt_reads_as_surface_topography() {
    let r = read("frt");
    assert_eq!(r.format, "frt");
    assert_eq!(r.channels.len(), 1);
    let c = &r.channels[0];
    assert!(c.is_height);
    // st_reference.py frt-1.frt: grid (500, 500), size (0.012, 0.012) m, pixel 2.4e-05 m,
    // masked 76456, rms 4.915785774480653e-06 m; height scale 9.765923032319103e-09 m per
    // count.
    check(
        c,
        &Ref {
            name: "frt",
            nx: 500,
            ny: 500,
            dx: 2.4e-05,
            dy: 2.4e-05,
            missing: 76456,
            rms: 4.915785774480653e-06,
            points: [
                (0, 0, 0.0),
                (499, 0, 0.0),
                (0, 499, f64::NAN),
                (250, 166, 7.887936033204139e-05),
            ],
        },
    );
    assert!((c.missing_fraction() - 76456.0 / 250000.0).abs() < 1e-15);
}

/// `r` is an input error that names `path` and says where: a line, or a byte offset.
fn assert_names_file(r: Result<Reading, Error>, path: &Path, case: &str) {
    match r {
        Err(e @ Error::Input { .. }) => {
            let Error::Input { path: p, line, msg } = &e else {
                unreachable!()
            };
            assert_eq!(p, path, "{case}: {e}");
            assert!(
                *line > 0 || msg.contains("byte"),
                "{case}: no line or offset: {e}"
            );
            assert!(
                e.to_string().starts_with(&path.display().to_string()),
                "{e}"
            );
        }
        Err(e) => panic!("{case}: expected an input error, got {e}"),
        Ok(r) => panic!("{case}: read {} channels", r.channels.len()),
    }
}

#[test]
fn truncated_files_are_errors_naming_the_file() {
    for (name, file, _, reader, needed) in FORMATS {
        let (p, bytes) = sample(file);
        // Every byte of the first 600, then 61 cuts across the part the reader needs.
        let cuts = (0..600).chain((0..=60).map(|k| 600 + (needed - 601) * k / 60));
        for cut in cuts {
            assert_names_file(
                reader(&p, &bytes[..cut]),
                &p,
                &format!("{name} cut at {cut}"),
            );
        }
        assert!(
            reader(&p, &bytes[..needed]).is_ok(),
            "{name}: needs only {needed} bytes"
        );
    }
}

#[test]
fn magic_tests_tell_the_formats_apart() {
    let files: Vec<_> = FORMATS.iter().map(|f| sample(f.1)).collect();
    for (i, (name, _, is, reader, _)) in FORMATS.into_iter().enumerate() {
        for (j, (p, bytes)) in files.iter().enumerate() {
            assert_eq!(is(bytes), i == j, "is_{name} on {}", p.display());
            if i != j {
                let case = format!("read_{name} on {}", p.display());
                assert_names_file(reader(p, bytes), p, &case);
            }
        }
        // The magic bytes (or, for PLU, the grid and type fields) zeroed.
        let (p, mut bytes) = sample(FORMATS[i].1);
        let zero = if name == "plu" { 388..432 } else { 0..12 };
        bytes[zero].fill(0);
        assert!(!is(&bytes), "{name} without its magic");
        assert_names_file(reader(&p, &bytes), &p, &format!("{name} without magic"));
    }
}

/// `bytes` with `old` (which must occur) replaced by `new`.
fn replace(bytes: &[u8], old: &[u8], new: &[u8]) -> Vec<u8> {
    let at = bytes.windows(old.len()).position(|w| w == old).unwrap();
    [&bytes[..at], new, &bytes[at + old.len()..]].concat()
}

/// `bytes` with every `old` replaced by `new`.
fn replace_all(bytes: &[u8], old: &[u8], new: &[u8]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    while let Some(at) = out.windows(old.len()).position(|w| w == old) {
        out.splice(at..at + old.len(), new.iter().copied());
    }
    out
}

/// `bytes` with `new` written at `off`.
fn patch(bytes: &[u8], off: usize, new: &[u8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[off..off + new.len()].copy_from_slice(new);
    b
}

#[test]
fn absurd_sizes_are_errors_not_allocations() {
    let giga = 1_000_000_000u32;
    let (_, m) = sample("metropro-1.dat");
    let (_, o) = sample("opd-1.opd");
    let (_, pl) = sample("plu-1.plu");
    let (_, d) = sample("di-1.di");
    let (_, mi) = sample("mi-1.mi");
    let (_, a) = sample("al3d-1.al3d");
    let (_, f) = sample("frt-1.frt");
    let tag = |v: &str| -> Vec<u8> {
        let mut t = v.as_bytes().to_vec();
        t.resize(30, 0);
        t
    };
    let cases: Vec<(&str, &str, Vec<u8>)> = vec![
        // Phase grid 65535 × 65535 (the largest the u16 fields hold), intensity buckets 65535.
        ("metropro", "phase grid", patch(&m, 68, &[0xff; 4])),
        ("metropro", "buckets", patch(&m, 56, &[0xff; 2])),
        ("metropro", "zero pixel", patch(&m, 184, &[0; 4])),
        // The 'Raw' array's 65535 × 65535 f32, then a directory longer than the file.
        ("opd", "array grid", patch(&o, 24020, &[0xff; 4])),
        ("opd", "directory", patch(&o, 20, &i32::MAX.to_le_bytes())),
        // 1e9 × 1e9 in both the calibration and the layer header; 255 layers.
        (
            "plu",
            "layer grid",
            patch(
                &patch(&pl, 388, &[giga.to_le_bytes(), giga.to_le_bytes()].concat()),
                500,
                &[giga.to_le_bytes(), giga.to_le_bytes()].concat(),
            ),
        ),
        ("plu", "layers", patch(&pl, 489, &[255])),
        // Every grid in the header, also the scan list's (which a reader falls back on when an
        // image's grid does not match its data length).
        (
            "di",
            "grid",
            replace_all(
                &replace_all(
                    &replace_all(&d, b"Samps/line: 512", b"Samps/line: 1000000000"),
                    b"Number of lines: 512",
                    b"Number of lines: 1000000000",
                ),
                b"\\Lines: 512",
                b"\\Lines: 1000000000",
            ),
        ),
        (
            "di",
            "offset",
            replace(&d, b"Data offset: 40960", b"Data offset: 99999999999999999"),
        ),
        (
            "di",
            "bytes/pixel",
            replace(&d, b"Bytes/pixel: 2", b"Bytes/pixel: 8"),
        ),
        (
            "mi",
            "grid",
            replace(&mi, b"xPixels       256", b"xPixels       1000000000"),
        ),
        (
            "mi",
            "zero size",
            replace(
                &mi,
                b"xLength       2.0000000000000002e-005",
                b"xLength       0",
            ),
        ),
        // The 'Cols' tag (the third) and TagCount.
        (
            "al3d",
            "cols",
            patch(&a, 17 + 2 * 52 + 20, &tag("1000000000")),
        ),
        (
            "al3d",
            "tag count",
            patch(&a, 17 + 52 + 20, &tag("999999999")),
        ),
        (
            "al3d",
            "offset",
            patch(&a, 17 + 6 * 52 + 20, &tag("18446744073709551615")),
        ),
        // Block 0x0066 at byte 32: nx, ny from byte 38; the first block's size at byte 20.
        (
            "frt",
            "grid",
            patch(&f, 38, &[giga.to_le_bytes(), giga.to_le_bytes()].concat()),
        ),
        ("frt", "block size", patch(&f, 20, &u32::MAX.to_le_bytes())),
        ("frt", "block count", patch(&f, 16, &u16::MAX.to_le_bytes())),
    ];
    for (name, case, bytes) in cases {
        let (_, file, is, reader, _) = FORMATS.iter().find(|f| f.0 == name).copied().unwrap();
        let p = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data/instrument")
            .join(file);
        assert!(is(&bytes), "{name} {case}: still looks like the format");
        assert_names_file(reader(&p, &bytes), &p, &format!("{name} {case}"));
    }
}

#[test]
fn corrupted_header_bytes_never_panic() {
    // Header bytes set to 0xff one at a time (each of the first 24, then 24 spread over the
    // rest of the header; each case reads the whole file, so they are few): an error or a reading, never a panic; a reading keeps its grid
    // consistent.
    for (name, file, _, reader, _) in FORMATS {
        let (p, bytes) = sample(file);
        let header = match name {
            "metropro" => 834,
            "plu" => 508,
            "al3d" => 1261,
            "frt" => 140,
            _ => 2000,
        };
        for off in (0..24).chain((0..24).map(|k| 24 + (header - 24) * k / 24)) {
            let b = patch(&bytes, off, &[0xff]);
            if let Ok(r) = reader(&p, &b) {
                for c in &r.channels {
                    assert_eq!(c.z.len(), c.nx * c.ny, "{name} byte {off}");
                    assert!(c.dx > 0.0 && c.dy > 0.0, "{name} byte {off}");
                }
            }
        }
    }
}

// Small files written here from the documented layouts, for the variants the samples do not
// have (sign flip and finest phase resolution, padded rows, 16-bit MI, 32-bit FRT images in
// the multi-image block). Expected heights are worked out from the layout by hand.

fn synthetic(name: &str) -> PathBuf {
    PathBuf::from(format!("synthetic.{name}"))
}

fn assert_heights(c: &Channel, want: &[f64]) {
    assert_eq!(c.z.len(), want.len(), "{}", c.name);
    for (k, (&got, &w)) in c.z.iter().zip(want).enumerate() {
        assert!(
            (got.is_nan() && w.is_nan()) || rel(got, w) <= 1e-15,
            "{} point {k}: {got:e}, expected {w:e}",
            c.name
        );
    }
}

#[test]
fn metropro_sign_resolution_and_invalid_marker() {
    let mut h = vec![0u8; 834];
    h[..4].copy_from_slice(&[0x88, 0x1b, 0x03, 0x6f]);
    h[4..6].copy_from_slice(&1u16.to_be_bytes());
    h[6..10].copy_from_slice(&834u32.to_be_bytes());
    h[68..70].copy_from_slice(&3u16.to_be_bytes());
    h[70..72].copy_from_slice(&2u16.to_be_bytes());
    h[164..168].copy_from_slice(&0.5f32.to_be_bytes());
    h[168..172].copy_from_slice(&6.328e-7f32.to_be_bytes());
    h[176..180].copy_from_slice(&1.25f32.to_be_bytes());
    h[184..188].copy_from_slice(&2e-6f32.to_be_bytes());
    h[218..220].copy_from_slice(&2i16.to_be_bytes());
    h[232..234].copy_from_slice(&1i16.to_be_bytes());
    let counts = [0i32, 1, -131072, 2147483640, 100, i32::MAX];
    h.extend(counts.iter().flat_map(|c| c.to_be_bytes()));
    let r = metropro::read_metropro(&synthetic("dat"), &h).unwrap();
    assert_eq!(r.channels.len(), 1, "no intensity buckets");
    let c = &r.channels[0];
    assert_eq!(
        (c.nx, c.ny, c.dx, c.dy),
        (3, 2, f64::from(2e-6f32), f64::from(2e-6f32))
    );
    // One count is -(0.5 · 1.25 · λ / 131072) m: sign field set, phase_res 2.
    let step = -0.5 * 1.25 * f64::from(6.328e-7f32) / 131072.0;
    let nan = f64::NAN;
    assert_heights(c, &[0.0, step, -131072.0 * step, nan, 100.0 * step, nan]);
}

#[test]
fn al3d_padded_rows_and_invalid_pixels() {
    let tag = |k: &str, v: &str| -> Vec<u8> {
        let mut t = vec![0u8; 52];
        t[..k.len()].copy_from_slice(k.as_bytes());
        t[20..20 + v.len()].copy_from_slice(v.as_bytes());
        t[50..].copy_from_slice(b"\r\n");
        t
    };
    // 17 bytes of magic, 2 + 7 tags, a 256-byte comment: the depth image at 17 + 9·52 + 256.
    let offset = (17 + 9 * 52 + 256).to_string();
    let mut f = b"AliconaImaging\0\r\n".to_vec();
    for (k, v) in [
        ("Version", "1"),
        ("TagCount", "7"),
        ("Cols", "3"),
        ("Rows", "2"),
        ("PixelSizeXMeter", "1e-06"),
        ("PixelSizeYMeter", "2e-06"),
        ("DepthImageOffset", offset.as_str()),
        ("InvalidPixelValue", "3e+15"),
        ("CreatingApplication", "test"),
    ] {
        f.extend(tag(k, v));
    }
    f.extend([0u8; 256]);
    // Rows of 3 f32 (12 bytes) padded to 16 with a value that must not be read.
    let rows = [[1.5f32, f32::NAN, 2.5, 99.0], [3e15, -4.0, 0.25, 99.0]];
    f.extend(rows.iter().flatten().flat_map(|v| v.to_le_bytes()));
    let r = al3d::read_al3d(&synthetic("al3d"), &f).unwrap();
    let c = &r.channels[0];
    assert_eq!((c.nx, c.ny, c.dx, c.dy), (3, 2, 1e-6, 2e-6));
    let nan = f64::NAN;
    assert_heights(c, &[1.5, nan, 2.5, nan, -4.0, 0.25]);
}

#[test]
fn mi_sixteen_bit_buffers() {
    let mut f = Vec::new();
    for (k, v) in [
        ("fileType", "Image"),
        ("xPixels", "3"),
        ("yPixels", "2"),
        ("xLength", "3e-6"),
        ("yLength", "4e-6"),
        ("bufferLabel", "Topography"),
        ("bufferRange", "1.5"),
        ("bufferUnit", "nm"),
        ("bufferLabel", "Amplitude"),
        ("bufferRange", "2"),
        ("bufferUnit", "V"),
        ("data", "BINARY"),
    ] {
        f.extend(format!("{k:<14}{v}\r\n").bytes());
    }
    // Two buffers, stored rows [1 2 3] then [4 5 -32768]: the last stored row is the top line.
    let counts: [i16; 12] = [1, 2, 3, 4, 5, -32768, 7, 8, 9, 10, 11, 12];
    f.extend(counts.iter().flat_map(|c| c.to_le_bytes()));
    let r = mi::read_mi(&synthetic("mi"), &f).unwrap();
    let c = &r.channels[0];
    assert_eq!((c.nx, c.ny, c.dx, c.dy), (3, 2, 1e-6, 2e-6));
    assert!(c.is_height && !r.channels[1].is_height);
    let s = 1.5 / 32768.0 * 1e-9;
    assert_heights(c, &[4.0 * s, 5.0 * s, -1.5e-9, s, 2.0 * s, 3.0 * s]);
    let v = 2.0 / 32768.0;
    assert_heights(
        &r.channels[1],
        &[10.0 * v, 11.0 * v, 12.0 * v, 7.0 * v, 8.0 * v, 9.0 * v],
    );
}

#[test]
fn frt_multi_image_block_with_32_bit_counts() {
    let block = |tag: u16, payload: Vec<u8>| -> Vec<u8> {
        let mut b = tag.to_le_bytes().to_vec();
        b.extend((payload.len() as u64).to_le_bytes());
        b.extend(payload);
        b
    };
    let f64s = |v: &[f64]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
    let mut size = f64s(&[6e-6, 4e-6, 0.0, 0.0, 1.0]);
    size.extend(0u32.to_le_bytes());
    let mut scale = 0u32.to_le_bytes().to_vec();
    scale.extend(2e-9f64.to_le_bytes());
    // Buffer ids, then a 32-bit topography image and a 16-bit intensity image (type 0x0002).
    let mut multi = vec![0u8; 8];
    for v in [0x0004u32, 3, 2, 32] {
        multi.extend(v.to_le_bytes());
    }
    multi.extend(
        [10i32, 1, -7, 70000, 5, 6]
            .iter()
            .flat_map(|c| c.to_le_bytes()),
    );
    for v in [0x0002u32, 3, 2, 16] {
        multi.extend(v.to_le_bytes());
    }
    multi.extend([0u8; 12]);
    let mut f = b"FRTM_GLIDERV1.01".to_vec();
    f.extend(3u16.to_le_bytes());
    f.extend(block(0x67, size));
    f.extend(block(0x6c, scale));
    f.extend(block(0x7d, multi));
    let r = frt::read_frt(&synthetic("frt"), &f).unwrap();
    assert_eq!(r.channels.len(), 1, "the intensity image is not a height");
    let c = &r.channels[0];
    assert_eq!(c.name, "Topography (top sensor) 1");
    assert_eq!((c.nx, c.ny, c.dx, c.dy), (3, 2, 2e-6, 2e-6));
    // The first stored row is the bottom line; count 1 is not measured.
    let s = 2e-9;
    assert_heights(
        c,
        &[70000.0 * s, 5.0 * s, 6.0 * s, 10.0 * s, f64::NAN, -7.0 * s],
    );
}
