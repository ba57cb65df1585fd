//! Instrument files (`coatcheck::instrument::read`): each format's real sample (tests/data/
//! instrument, see its README) read as the reference library reads it, files written here
//! following the formats' documentation, and hostile files (truncated, wrong signature, absurd
//! sizes) that must give an error naming the file, never a panic or a huge allocation.
//!
//! Reference values: SurfaceTopography 1.27.1 (`pip install SurfaceTopography==1.27.1` in a
//! scratch venv), read with `open_topography(f).topography()`; sizes are its
//! `physical_sizes` converted to m with its unit; h_rms is `sqrt(mean((h - mean(h))^2))` of the
//! unmasked heights in m, printed with `%.17g` (here in the shortest form that rounds to the same double). The script is tests/data/instrument/st_ref.py:
//! `/tmp/st/bin/python tests/data/instrument/st_ref.py tests/data/instrument/<file>`.

use std::path::{Path, PathBuf};

use coatcheck::Error;
use coatcheck::instrument::{Channel, read};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/instrument")
        .join(name)
}

/// rms about the mean of the measured (non-NaN) heights, and how many are missing.
fn h_rms(c: &Channel) -> (f64, usize) {
    let v: Vec<f64> = c.z.iter().copied().filter(|z| !z.is_nan()).collect();
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    let var = v.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / v.len() as f64;
    (var.sqrt(), c.z.len() - v.len())
}

fn assert_rel(what: &str, got: f64, want: f64, rel: f64) {
    assert!(
        (got - want).abs() <= rel * want.abs(),
        "{what}: got {got:e}, want {want:e} (relative tolerance {rel:e})"
    );
}

/// Checks the one channel of `name` against the reference: format, grid, size per axis (m),
/// height unit, h_rms (m) and the number of points not measured.
#[allow(clippy::too_many_arguments)]
fn check_sample(
    name: &str,
    format: &str,
    grid: (usize, usize),
    size: (f64, f64),
    unit: &str,
    rms: f64,
    missing: usize,
) -> Channel {
    let r = read(&data(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(r.format, format);
    assert_eq!(r.channels.len(), 1);
    let c = r.channels[r.default_channel()].clone();
    assert!(c.is_height);
    assert_eq!((c.nx, c.ny), grid, "{name}: grid");
    assert_eq!(c.z.len(), c.nx * c.ny);
    assert_rel("size x", c.dx * c.nx as f64, size.0, 1e-12);
    assert_rel("size y", c.dy * c.ny as f64, size.1, 1e-12);
    assert_eq!(c.unit_in_file, unit);
    let (got, miss) = h_rms(&c);
    assert_eq!(miss, missing, "{name}: points not measured");
    assert_rel("h_rms", got, rms, 1e-9);
    c
}

#[test]
fn x3p_sample_as_surfacetopography_reads_it() {
    // SurfaceTopography: grid (650, 650), physical_sizes (8.29767313942749e-05,
    // 0.0002044783737930349) m, h_rms 7.728033273597876e-08 m, no masked point.
    check_sample(
        "x3p-2.x3p",
        "x3p",
        (650, 650),
        (8.29767313942749e-05, 0.0002044783737930349),
        "m",
        7.728033273597876e-08,
        0,
    );
}

#[test]
fn sur_sample_as_surfacetopography_reads_it() {
    // SurfaceTopography: grid (563, 484), physical_sizes (1.9614921233151108,
    // 1.6862561060115695) mm, 117 masked points (z min − 2), h_rms 1.7517881243588177e-08 m.
    let c = check_sample(
        "sur-2.sur",
        "sur",
        (563, 484),
        (1.9614921233151108e-3, 1.6862561060115695e-3),
        "mm",
        1.7517881243588177e-08,
        117,
    );
    assert_eq!(c.name, "Z");
}

#[test]
fn sdf_sample_as_surfacetopography_reads_it() {
    // SurfaceTopography: grid (7, 4), physical_sizes (7.0, 4.0) µm, h_rms
    // 1.3602897289488263e-08 m. The file is ISO 25178-71's example (Xscale = Yscale = 1e-6 m).
    let c = check_sample(
        "sdf-1.sdf",
        "sdf",
        (7, 4),
        (7e-6, 4e-6),
        "m",
        1.3602897289488263e-08,
        0,
    );
    // Second profile, first point: 0.99874 · Zscale (1e-6 m).
    assert_rel("z[1, 0]", c.z[7], 0.99874e-6, 1e-15);
}

#[test]
fn gwyddion_export_as_surfacetopography_reads_it() {
    // SurfaceTopography: grid (3, 4), physical_sizes (1.2339999999999999e-05, 5.6789e-06) m
    // (Width 12.34 µm, Height 5678.9 nm), h_rms 4.70575150451256 m (values in m).
    let c = check_sample(
        "gwyddion-export-english.txt",
        "gwyddion-txt",
        (3, 4),
        (1.2339999999999999e-05, 5.6789e-06),
        "m",
        4.70575150451256,
        0,
    );
    assert_eq!(c.name, "My Channel Name");
    assert_eq!(
        c.z,
        [
            1.0, 1.5, 3.0, -2.0, -3.0, -6.0, 0.0, 0.0, 0.0, 9.0, 9.0, 9.0
        ]
    );
}

#[test]
fn dektak_profile_as_surfacetopography_reads_it() {
    // SurfaceTopography reads it as a non-uniform line scan of 9600 points over x from 0 to
    // 1499.8 µm (physical_sizes 1499.8 µm, the x range), h_rms 4.764232930211045e-06 m. Here
    // the grid is uniform with the mean step, so (n − 1)·dx is that range.
    let r = read(&data("dektak-1.csv")).unwrap();
    assert_eq!(r.format, "dektak");
    let c = &r.channels[0];
    assert_eq!((c.nx, c.ny), (9600, 1));
    assert_rel("x range", c.dx * 9599.0, 1499.8e-6, 1e-12);
    assert_eq!(c.dy, c.dx);
    assert_eq!(c.unit_in_file, "Micrometer");
    let (rms, missing) = h_rms(c);
    assert_eq!(missing, 0);
    assert_rel("h_rms", rms, 4.764232930211045e-06, 1e-9);
    // First point: z = -0.00933 µm.
    assert_rel("z[0]", c.z[0], -0.00933e-6, 1e-15);
}

#[test]
fn mitutoyo_profile_as_surfacetopography_reads_it() {
    // SurfaceTopography: uniform line scan of 960 points, physical_sizes 480.0 µm (n · dx,
    // x from 0.0005 mm in steps of 0.0005 mm), h_rms 1.6866328079293707e-07 m (heights in µm,
    // the unit of "Ra 0.018 µm").
    let c = check_sample(
        "mitutoyo_mock.xlsx",
        "mitutoyo",
        (960, 1),
        (480e-6, 0.5e-6),
        "µm",
        1.6866328079293707e-07,
        0,
    );
    // First height: cell F1 = 0.303327568640866 µm.
    assert_rel("z[0]", c.z[0], 0.303327568640866e-6, 1e-15);
}

#[test]
fn gwy_written_by_surfacetopography() {
    // Written by SurfaceTopography's GWY writer (tests/data/instrument/make_gwy.py) from the
    // Gwyddion ASCII sample; it reads it back as grid (3, 4), physical_sizes
    // (1.2339999999999999e-05, 5.6789e-06) m, h_rms 4.70575150451256 m.
    let c = check_sample(
        "st-gwyddion-export.gwy",
        "gwy",
        (3, 4),
        (1.2339999999999999e-05, 5.6789e-06),
        "m",
        4.70575150451256,
        0,
    );
    assert_eq!(c.name, "My Channel Name");
    assert_eq!(
        c.z,
        [
            1.0, 1.5, 3.0, -2.0, -3.0, -6.0, 0.0, 0.0, 0.0, 9.0, 9.0, 9.0
        ]
    );
    // A 5 × 3 map in µm with points (x, y) = (1, 0) and (4, 2) masked; SurfaceTopography reads
    // back physical_sizes (2e-06, 1.5e-06) m, 2 masked, h_rms 9.680548422040936e-07 m.
    let c = check_sample(
        "st-masked.gwy",
        "gwy",
        (5, 3),
        (2e-6, 1.5e-6),
        "m",
        9.680548422040936e-07,
        2,
    );
    assert!(c.z[1].is_nan() && c.z[2 * 5 + 4].is_nan());
    // h[x, y] = (5 y + x) · 0.25 − 1 µm.
    assert_rel("z[3, 1]", c.z[5 + 3], (8.0 * 0.25 - 1.0) * 1e-6, 1e-15);
}

/// A Gwyddion file following the documented serialisation ("GWYP", objects of named, typed
/// components), with no sample from the instrument software: a height field in m, a phase
/// field in deg (not a height) and components of every other type that must be skipped.
fn gwy_file() -> Vec<u8> {
    fn cstr(out: &mut Vec<u8>, s: &str) {
        out.extend_from_slice(s.as_bytes());
        out.push(0);
    }
    fn object(name: &str, components: &[(&str, u8, Vec<u8>)]) -> Vec<u8> {
        let mut body = Vec::new();
        for (k, t, v) in components {
            cstr(&mut body, k);
            body.push(*t);
            body.extend_from_slice(v);
        }
        let mut out = Vec::new();
        cstr(&mut out, name);
        out.extend_from_slice(&(body.len() as u32).to_le_bytes());
        out.extend_from_slice(&body);
        out
    }
    fn unit(s: &str) -> Vec<u8> {
        let mut v = Vec::new();
        cstr(&mut v, s);
        object("GwySIUnit", &[("unitstr", b's', v)])
    }
    fn field(nx: i32, ny: i32, xreal: f64, yreal: f64, z_unit: &str, z: &[f64]) -> Vec<u8> {
        let mut data = (z.len() as u32).to_le_bytes().to_vec();
        z.iter()
            .for_each(|v| data.extend_from_slice(&v.to_le_bytes()));
        object(
            "GwyDataField",
            &[
                ("xres", b'i', nx.to_le_bytes().to_vec()),
                ("yres", b'i', ny.to_le_bytes().to_vec()),
                ("xreal", b'd', xreal.to_le_bytes().to_vec()),
                ("yreal", b'd', yreal.to_le_bytes().to_vec()),
                ("xoff", b'd', 0f64.to_le_bytes().to_vec()),
                ("si_unit_xy", b'o', unit("m")),
                ("si_unit_z", b'o', unit(z_unit)),
                ("data", b'D', data),
            ],
        )
    }
    let mut title = Vec::new();
    cstr(&mut title, "Height");
    let strings = [2u32.to_le_bytes().to_vec(), b"a\0bc\0".to_vec()].concat();
    let ints = [2u32.to_le_bytes().to_vec(), vec![1, 0, 0, 0, 2, 0, 0, 0]].concat();
    let mut out = b"GWYP".to_vec();
    out.extend(object(
        "GwyContainer",
        &[
            ("/0/data/visible", b'b', vec![1]),
            ("/0/data/title", b's', title),
            ("/0/base/range-type", b'i', 1i32.to_le_bytes().to_vec()),
            ("/0/meta/n", b'q', 7i64.to_le_bytes().to_vec()),
            ("/0/meta/ints", b'I', ints),
            ("/0/meta/strings", b'S', strings),
            (
                "/1/data",
                b'o',
                field(2, 3, 4e-6, 9e-6, "deg", &[1.0, 2.0, 3.0, 4.0, 5.0, 6.0]),
            ),
            (
                "/0/data",
                b'o',
                field(3, 2, 6e-6, 2e-6, "m", &[1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9]),
            ),
        ],
    ));
    out
}

#[test]
fn gwy_written_from_the_documented_format() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("doc.gwy");
    std::fs::write(&path, gwy_file()).unwrap();
    let r = read(&path).unwrap();
    assert_eq!(r.format, "gwy");
    assert_eq!(r.channels.len(), 2);
    assert_eq!(r.default_channel(), 0);
    let h = &r.channels[0];
    assert_eq!((h.name.as_str(), h.nx, h.ny), ("Height", 3, 2));
    assert_eq!((h.dx, h.dy), (2e-6, 1e-6));
    assert_eq!(h.z, [1e-9, 2e-9, 3e-9, 4e-9, 5e-9, 6e-9]);
    let p = &r.channels[1];
    assert_eq!(
        (p.name.as_str(), p.nx, p.ny, p.is_height),
        ("/1/data", 2, 3, false)
    );
    assert_eq!((p.dx, p.dy, p.unit_in_file.as_str()), (2e-6, 3e-6, "deg"));
}

/// CRC-32 (reflected, 0xEDB88320), for the archives written here.
fn crc32(data: &[u8]) -> u32 {
    let mut c = !0u32;
    for &b in data {
        c ^= u32::from(b);
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xedb8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// A ZIP archive of stored (uncompressed) members, per PKWARE's APPNOTE.
fn zip_stored(members: &[(&str, &[u8])]) -> Vec<u8> {
    let (mut out, mut dir) = (Vec::new(), Vec::new());
    for (name, data) in members {
        let offset = out.len() as u32;
        let common = |v: &mut Vec<u8>| {
            v.extend_from_slice(&[20, 0, 0, 0, 0, 0, 0, 0, 0, 0]);
            v.extend_from_slice(&crc32(data).to_le_bytes());
            v.extend_from_slice(&(data.len() as u32).to_le_bytes());
            v.extend_from_slice(&(data.len() as u32).to_le_bytes());
            v.extend_from_slice(&(name.len() as u16).to_le_bytes());
            v.extend_from_slice(&[0, 0]);
        };
        out.extend_from_slice(b"PK\x03\x04");
        common(&mut out);
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(data);
        dir.extend_from_slice(b"PK\x01\x02\x14\x00");
        common(&mut dir);
        // Comment length, disk, internal and external attributes.
        dir.extend_from_slice(&[0; 10]);
        dir.extend_from_slice(&offset.to_le_bytes());
        dir.extend_from_slice(name.as_bytes());
    }
    let at = out.len() as u32;
    out.extend_from_slice(&dir);
    out.extend_from_slice(b"PK\x05\x06\0\0\0\0");
    let n = (members.len() as u16).to_le_bytes();
    out.extend_from_slice(&[n[0], n[1], n[0], n[1]]);
    out.extend_from_slice(&(dir.len() as u32).to_le_bytes());
    out.extend_from_slice(&at.to_le_bytes());
    out.extend_from_slice(&[0, 0]);
    out
}

/// main.xml of a 3 × 2 map with CZ of type `ty`, its increment and offset, and the members.
fn x3p_main(ty: &str, cz_extra: &str, sizes: (&str, &str), valid: bool) -> String {
    let valid = if valid {
        "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>"
    } else {
        ""
    };
    format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
 <Record1><Revision>ISO5436 - 2000</Revision><FeatureType>SUR</FeatureType><Axes>
  <CX><AxisType>I</AxisType><DataType>D</DataType><Increment>2.5e-7</Increment><Offset>0</Offset></CX>
  <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>5e-7</Increment></CY>
  <CZ><AxisType>A</AxisType><DataType>{ty}</DataType>{cz_extra}</CZ></Axes></Record1>
 <Record3><MatrixDimension><SizeX>{}</SizeX><SizeY>{}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
  <DataLink><PointDataLink>bindata/data.bin</PointDataLink>{valid}</DataLink></Record3>
</p:ISO5436_2>"#,
        sizes.0, sizes.1
    )
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

#[test]
fn x3p_data_types_increment_offset_and_valid_points() {
    let dir = tempfile::tempdir().unwrap();
    let raw = [-3i64, -1, 0, 1, 2, 300];
    let cases: [(&str, Vec<u8>); 4] = [
        (
            "I",
            raw.iter().flat_map(|&v| (v as i16).to_le_bytes()).collect(),
        ),
        (
            "L",
            raw.iter().flat_map(|&v| (v as i32).to_le_bytes()).collect(),
        ),
        (
            "F",
            raw.iter().flat_map(|&v| (v as f32).to_le_bytes()).collect(),
        ),
        (
            "D",
            raw.iter().flat_map(|&v| (v as f64).to_le_bytes()).collect(),
        ),
    ];
    // Valid bits, least significant first: point 4 (x 1, y 1) not measured.
    let valid = [0b0010_1111u8];
    for (ty, bin) in &cases {
        let main = x3p_main(
            ty,
            "<Increment>1e-9</Increment><Offset>2e-6</Offset>",
            ("3", "2"),
            true,
        );
        let file = zip_stored(&[
            ("main.xml", main.as_bytes()),
            ("bindata/data.bin", bin),
            ("bindata/valid.bin", &valid),
        ]);
        let c = read(&write(dir.path(), "t.x3p", &file))
            .unwrap()
            .channels
            .remove(0);
        assert_eq!((c.nx, c.ny, c.dx, c.dy), (3, 2, 2.5e-7, 5e-7), "type {ty}");
        for (i, (&z, &r)) in c.z.iter().zip(&raw).enumerate() {
            if i == 4 {
                assert!(z.is_nan(), "type {ty}: point 4 is not measured");
            } else {
                assert_eq!(z, r as f64 * 1e-9 + 2e-6, "type {ty}, point {i}");
            }
        }
    }
    // Float heights without increment or offset are metres; NaN is not measured.
    let bin: Vec<u8> = [1e-6, f64::NAN, 3e-6, 4e-6, 5e-6, 6e-6]
        .iter()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let main = x3p_main("D", "", ("3", "2"), false);
    let file = zip_stored(&[("main.xml", main.as_bytes()), ("bindata/data.bin", &bin)]);
    let c = read(&write(dir.path(), "t.x3p", &file))
        .unwrap()
        .channels
        .remove(0);
    assert_eq!(c.missing_fraction(), 1.0 / 6.0);
    assert_eq!(c.z[5], 6e-6);
}

/// Asserts that reading `path` fails with an input error naming the file whose message
/// contains `needle`.
fn assert_refused(path: &Path, needle: &str) {
    match read(path) {
        Err(e @ Error::Input { .. }) => {
            let msg = e.to_string();
            assert!(msg.contains(&path.display().to_string()), "{msg}");
            assert!(msg.contains(needle), "expected '{needle}' in: {msg}");
        }
        other => panic!("{}: expected an input error, got {other:?}", path.display()),
    }
}

#[test]
fn hostile_x3p() {
    let dir = tempfile::tempdir().unwrap();
    let real = std::fs::read(data("x3p-2.x3p")).unwrap();
    assert_refused(
        &write(dir.path(), "cut.x3p", &real[..real.len() / 2]),
        "end-of-central-directory",
    );
    let mut magic = real.clone();
    magic[..4].copy_from_slice(b"XXXX");
    let p = write(dir.path(), "magic.x3p", &magic[..100]);
    assert_refused(&p, "not a ZIP archive");
    // The header claims 1e9 × 1e9 points: refused before the data are inflated.
    let main = x3p_main("D", "", ("1000000000", "1000000000"), false);
    let file = zip_stored(&[
        ("main.xml", main.as_bytes()),
        ("bindata/data.bin", &[0u8; 48]),
    ]);
    assert_refused(
        &write(dir.path(), "huge.x3p", &file),
        "needs 8000000000000000000",
    );
    // A corrupt member is caught by its CRC.
    let main = x3p_main("D", "", ("3", "2"), false);
    let mut file = zip_stored(&[
        ("main.xml", main.as_bytes()),
        ("bindata/data.bin", &[0u8; 48]),
    ]);
    // The last member's data end where the central directory starts.
    let at = file.windows(4).position(|w| w == b"PK\x01\x02").unwrap() - 10;
    file[at] ^= 0xff;
    assert_refused(&write(dir.path(), "crc.x3p", &file), "CRC-32");
}

/// Writes `bytes` with field `at` (a little-endian u32/i32) set to `v`.
fn patch32(bytes: &[u8], at: usize, v: u32) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at..at + 4].copy_from_slice(&v.to_le_bytes());
    b
}

#[test]
fn hostile_sur() {
    let dir = tempfile::tempdir().unwrap();
    let real = std::fs::read(data("sur-2.sur")).unwrap();
    assert_refused(
        &write(dir.path(), "cut.sur", &real[..real.len() - 1]),
        "byte 512",
    );
    assert_refused(&write(dir.path(), "head.sur", &real[..100]), "byte 100");
    let mut magic = real.clone();
    magic[0] = b'X';
    assert_refused(&write(dir.path(), "magic.sur", &magic), "DIGITAL SURF");
    // 40000 × 40000 points of 4 bytes (6.4 GB) in a 1 MB file.
    let huge = patch32(
        &patch32(&patch32(&real, 108, 40000), 112, 40000),
        116,
        1_600_000_000,
    );
    assert_refused(
        &write(dir.path(), "huge.sur", &huge),
        "needs 6400000000 bytes",
    );
    let wrong_count = patch32(&real, 116, 7);
    assert_refused(&write(dir.path(), "count.sur", &wrong_count), "byte 116");
}

#[test]
fn hostile_sdf() {
    let dir = tempfile::tempdir().unwrap();
    let real = std::fs::read_to_string(data("sdf-1.sdf")).unwrap();
    // Cut after the third of four profiles: the error is at the last line.
    let cut = &real[..real.find("0.97986 0.97862").unwrap()];
    let e = read(&write(dir.path(), "cut.sdf", cut.as_bytes())).unwrap_err();
    assert!(matches!(e, Error::Input { line: 17, .. }), "{e}");
    assert!(e.to_string().contains("21 values"), "{e}");
    assert_refused(
        &write(
            dir.path(),
            "magic.sdf",
            real.replacen("aISO", "xISO", 1).as_bytes(),
        ),
        "signature",
    );
    let huge = real.replace("NumPoints = 7", "NumPoints = 1000000000");
    assert_refused(
        &write(dir.path(), "huge.sdf", huge.as_bytes()),
        "1000000000 × 4 points",
    );
    let bad = real.replace("0.99748", "0.99x48");
    let e = read(&write(dir.path(), "bad.sdf", bad.as_bytes())).unwrap_err();
    assert!(matches!(e, Error::Input { line: 16, .. }), "{e}");
    // Binary SDF: a 2 × 1 grid of i16 with the invalid marker, then truncated and oversized.
    let mut bin = b"bISO-1.0".to_vec();
    bin.extend_from_slice(&[b' '; 34]);
    bin.extend_from_slice(&2u16.to_le_bytes());
    bin.extend_from_slice(&1u16.to_le_bytes());
    for s in [1e-6f64, 1e-6, 1e-9, 1e-9] {
        bin.extend_from_slice(&s.to_le_bytes());
    }
    bin.extend_from_slice(&[0, 5, 0]);
    bin.extend_from_slice(&7i16.to_le_bytes());
    bin.extend_from_slice(&i16::MIN.to_le_bytes());
    let c = read(&write(dir.path(), "b.sdf", &bin))
        .unwrap()
        .channels
        .remove(0);
    assert_eq!((c.nx, c.ny, c.dx), (2, 1, 1e-6));
    assert_eq!(c.z[0], 7.0 * 1e-9);
    assert!(c.z[1].is_nan());
    assert_refused(
        &write(dir.path(), "bcut.sdf", &bin[..bin.len() - 1]),
        "byte 81",
    );
}

#[test]
fn hostile_gwy() {
    let dir = tempfile::tempdir().unwrap();
    let good = gwy_file();
    assert_refused(
        &write(dir.path(), "cut.gwy", &good[..good.len() - 3]),
        "truncated",
    );
    let mut magic = good.clone();
    magic[..4].copy_from_slice(b"GWYO");
    assert_refused(&write(dir.path(), "magic.gwy", &magic), "GWYP");
    // xres of the height field (the second "xres" in the file) set to 1e9.
    let i = good.windows(5).rposition(|w| w == b"xres\0").unwrap() + 6;
    let huge = patch32(&good, i, 1_000_000_000);
    assert_refused(
        &write(dir.path(), "huge.gwy", &huge),
        "1000000000 × 2 points",
    );
    // Objects nested beyond any real file.
    let mut deep = b"GWYP".to_vec();
    for _ in 0..100 {
        deep.extend_from_slice(b"GwyContainer\0\xff\xff\x00\x00x\0o");
    }
    deep.resize(deep.len() + 70000, 0);
    assert_refused(&write(dir.path(), "deep.gwy", &deep), "nested deeper");
}

#[test]
fn hostile_text_exports() {
    let dir = tempfile::tempdir().unwrap();
    let gwy = std::fs::read_to_string(data("gwyddion-export-english.txt")).unwrap();
    let ragged = gwy.trim_end().trim_end_matches('9').to_string();
    let e = read(&write(dir.path(), "ragged.txt", ragged.as_bytes())).unwrap_err();
    assert!(matches!(e, Error::Input { line: 8, .. }), "{e}");
    let e = read(&write(
        dir.path(),
        "w.txt",
        gwy.replace("12.34 µm", "12.34 parsecs").as_bytes(),
    ))
    .unwrap_err();
    assert!(matches!(e, Error::Input { line: 2, .. }), "{e}");
    let dektak = std::fs::read(data("dektak-1.csv")).unwrap();
    let scan_data = dektak.windows(9).position(|w| w == b"Scan Data").unwrap();
    assert_refused(
        &write(dir.path(), "cut.csv", &dektak[..scan_data]),
        "Scan Data",
    );
    // Cut within the last number: "1499.8,16.58112,," becomes "1499.8,16.58".
    let mid = &dektak[..dektak.len() - 10];
    assert!(mid.ends_with(b"1499.8,16.58"));
    let e = read(&write(dir.path(), "mid.csv", mid)).unwrap_err();
    assert!(matches!(e, Error::Input { line: 9628, .. }), "{e}");
    let mut magic = dektak.clone();
    magic[0] = b'X';
    assert!(
        read(&write(dir.path(), "magic.csv", &magic))
            .is_err_and(|e| e.to_string().contains("instrument"))
    );
    let xlsx = std::fs::read(data("mitutoyo_mock.xlsx")).unwrap();
    assert_refused(
        &write(dir.path(), "cut.xlsx", &xlsx[..xlsx.len() / 2]),
        "end-of-central-directory",
    );
}

/// Every prefix length and single-byte corruption sampled over each sample: an error or a
/// reading, never a panic.
#[test]
fn damaged_samples_never_panic() {
    let dir = tempfile::tempdir().unwrap();
    for name in [
        "x3p-2.x3p",
        "sur-2.sur",
        "sdf-1.sdf",
        "gwyddion-export-english.txt",
        "dektak-1.csv",
        "mitutoyo_mock.xlsx",
        "st-masked.gwy",
    ] {
        let real = std::fs::read(data(name)).unwrap();
        let ext = Path::new(name).extension().unwrap().to_str().unwrap();
        let step = (real.len() / 40).max(1);
        for (k, cut) in (0..real.len()).step_by(step).enumerate() {
            let _ = read(&write(dir.path(), &format!("c.{ext}"), &real[..cut]));
            let mut flipped = real.clone();
            let at = (cut * 7 + k) % real.len().min(4096);
            flipped[at] ^= 0x5a;
            let _ = read(&write(dir.path(), &format!("f.{ext}"), &flipped));
        }
    }
}
