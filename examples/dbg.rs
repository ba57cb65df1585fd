use coatcheck::contact::{Engine, Request};
use coatcheck::layer::{Bilayer, Elastic, Stack};
use coatcheck::prec::Settings;
use coatcheck::psd::{Spectrum, Tabulated};
fn main() {
    let n = 1000;
    let q: Vec<f64> = (0..n)
        .map(|i| 1e4 * 1e4f64.powf(i as f64 / (n - 1) as f64))
        .collect();
    let c: Vec<f64> = q
        .iter()
        .map(|&q| {
            let base = if q < 3e4 {
                1.0
            } else {
                (q / 3e4).powf(-2.0 * 1.8)
            };
            base * (1.0 + 0.03 * (7.0 * q.ln()).sin())
        })
        .collect();
    let sp = Spectrum::Tabulated(Tabulated::new(q, c).unwrap())
        .scaled_to_rms_slope(0.5)
        .unwrap();
    let pair = Bilayer::new(
        Elastic::new(1e6, 0.5).unwrap(),
        Elastic::new(2e11, 0.3).unwrap(),
    );
    let e = Engine::new(&sp, Settings { rtol: 1e-8 });
    let c = e
        .evaluate(
            &Stack::new(pair, 20e-6).unwrap(),
            1e5,
            Request {
                tau_interface: true,
                ..Default::default()
            },
        )
        .unwrap();
    println!("{:?}", c.tau_rms_interface);
}
