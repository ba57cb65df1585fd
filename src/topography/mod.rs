//! Surface topography: height data, their power spectra, and synthetic surfaces (issue 4).
//!
//! - [`convert`]: the exact 1D ↔ 2D PSD relation of an isotropic surface (Abel pair), and the
//!   normalisation conventions of both spectra.

pub mod convert;
