//! coatcheck: qualify a soft coating bonded to a hard substrate against surface roughness.
//!
//! Persson's contact mechanics for a layered solid (paper: `../shared/theory/paper.md`;
//! conventions: `../shared/theory/notes.md`). The physics lives here, independent of the
//! command line:
//!
//! - [`psd`]: roughness power spectra C(q) (tabulated and models, eqs. 2 and 5) and their moments;
//! - [`layer`]: the layered response S(q) of eq. (7) and the static interface kernels f, g (App. B);
//! - [`contact`]: G(q), P(q), A/A0 (eqs. B11, B12), rms stresses (B8–B10), distributions, E_eff;
//! - [`prec`]: tolerances, [`prec::Estimate`] (value, error, termination).
//!
//! Units are SI throughout (Pa, m, 1/m, m^4).

pub mod batch;
pub mod bem;
pub mod cheb;
pub mod check;
pub mod contact;
pub mod error;
pub mod exact;
pub mod figures;
pub mod instrument;
pub mod layer;
pub mod material;
pub mod pipeline;
pub mod prec;
pub mod psd;
pub mod quad;
pub mod report;
pub mod scene;
mod simd;
pub mod special;
pub mod tail;
pub mod textio;
pub mod tomlin;
pub mod topography;
pub mod units;
pub mod verify;
pub mod verify_stack;

pub use error::Error;
