//! Benchmark of `instrument::read` on a 2048 × 2048 map (4.2 million points) in three binary
//! formats written to a temporary directory: Digital Surf SUR (32-bit integers), binary
//! ISO 25178-71 SDF (64-bit floats) and Gwyddion GWY (64-bit floats). Prints the median of
//! 7 reads per format: file read, parse and conversion to metres.
//!
//! Run: `cargo run --release --example bench_read`

use std::path::Path;
use std::time::{Duration, Instant};

use coatcheck::instrument::read;

const N: usize = 2048;

/// Height of point (ix, iy), in units of the file's height step.
fn height(ix: usize, iy: usize) -> f64 {
    ((ix * 7919 + iy * 104_729) % 20_001) as f64 - 10_000.0
}

fn sur() -> Vec<u8> {
    let mut b = vec![0u8; 512];
    b[..12].copy_from_slice(b"DIGITAL SURF");
    b[14..16].copy_from_slice(&1u16.to_le_bytes());
    b[98..100].copy_from_slice(&32u16.to_le_bytes());
    b[108..112].copy_from_slice(&(N as i32).to_le_bytes());
    b[112..116].copy_from_slice(&(N as i32).to_le_bytes());
    b[116..120].copy_from_slice(&((N * N) as u32).to_le_bytes());
    for (at, v) in [(120, 0.5f32), (124, 0.5), (128, 1e-3)] {
        b[at..at + 4].copy_from_slice(&v.to_le_bytes());
    }
    for at in [180, 196, 212] {
        b[at..at + 2].copy_from_slice(b"um");
    }
    for iy in 0..N {
        for ix in 0..N {
            b.extend_from_slice(&(height(ix, iy) as i32).to_le_bytes());
        }
    }
    b
}

fn sdf() -> Vec<u8> {
    let mut b = b"bISO-1.0".to_vec();
    b.extend_from_slice(&[b' '; 34]);
    b.extend_from_slice(&(N as u16).to_le_bytes());
    b.extend_from_slice(&(N as u16).to_le_bytes());
    for s in [5e-7f64, 5e-7, 1e-9, 1e-9] {
        b.extend_from_slice(&s.to_le_bytes());
    }
    b.extend_from_slice(&[0, 7, 0]);
    for iy in 0..N {
        for ix in 0..N {
            b.extend_from_slice(&height(ix, iy).to_le_bytes());
        }
    }
    b
}

fn gwy() -> Vec<u8> {
    fn comp(out: &mut Vec<u8>, name: &str, ty: u8, value: &[u8]) {
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&[0, ty]);
        out.extend_from_slice(value);
    }
    fn object(name: &str, body: &[u8]) -> Vec<u8> {
        let mut o = name.as_bytes().to_vec();
        o.push(0);
        o.extend_from_slice(&(body.len() as u32).to_le_bytes());
        o.extend_from_slice(body);
        o
    }
    let mut unit = Vec::new();
    comp(&mut unit, "unitstr", b's', b"m\0");
    let unit = object("GwySIUnit", &unit);
    let mut data = ((N * N) as u32).to_le_bytes().to_vec();
    for iy in 0..N {
        for ix in 0..N {
            data.extend_from_slice(&(height(ix, iy) * 1e-9).to_le_bytes());
        }
    }
    let mut field = Vec::new();
    comp(&mut field, "xres", b'i', &(N as i32).to_le_bytes());
    comp(&mut field, "yres", b'i', &(N as i32).to_le_bytes());
    comp(&mut field, "xreal", b'd', &1.024e-3f64.to_le_bytes());
    comp(&mut field, "yreal", b'd', &1.024e-3f64.to_le_bytes());
    comp(&mut field, "si_unit_xy", b'o', &unit);
    comp(&mut field, "si_unit_z", b'o', &unit);
    comp(&mut field, "data", b'D', &data);
    let mut container = Vec::new();
    comp(
        &mut container,
        "/0/data",
        b'o',
        &object("GwyDataField", &field),
    );
    let mut b = b"GWYP".to_vec();
    b.extend(object("GwyContainer", &container));
    b
}

fn median_read(path: &Path) -> Duration {
    let mut t: Vec<Duration> = (0..7)
        .map(|_| {
            let start = Instant::now();
            let r = read(path).expect("benchmark file reads");
            let elapsed = start.elapsed();
            assert_eq!(r.channels[0].z.len(), N * N);
            elapsed
        })
        .collect();
    t.sort();
    t[t.len() / 2]
}

fn main() {
    let dir = tempfile::tempdir().expect("temporary directory");
    println!("instrument::read, {N} × {N} map, median of 7 reads");
    println!("{:<6} {:>10} {:>12}", "format", "file MB", "median ms");
    for (name, bytes) in [("sur", sur()), ("sdf", sdf()), ("gwy", gwy())] {
        let path = dir.path().join(format!("map.{name}"));
        std::fs::write(&path, &bytes).expect("write benchmark file");
        let t = median_read(&path);
        println!(
            "{name:<6} {:>10.1} {:>12.1}",
            bytes.len() as f64 / 1e6,
            t.as_secs_f64() * 1e3
        );
    }
}
