//! Layered response: S(q) of eq. (7) and the static interface kernels f(qd), g(qd).
//! (Skeleton: the stable forms are filled in by the engine commit.)

use crate::error::Error;
use serde::Serialize;

/// An isotropic linear-elastic material: Young's modulus (Pa) and Poisson ratio in [0, 0.5].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Elastic {
    pub youngs: f64,
    pub poisson: f64,
}

impl Elastic {
    pub fn new(youngs: f64, poisson: f64) -> Result<Self, Error> {
        if !(youngs.is_finite() && youngs > 0.0) {
            return Err(Error::invalid(
                "Young's modulus",
                youngs,
                "a finite E > 0 in Pa",
            ));
        }
        if !(poisson.is_finite() && (0.0..=0.5).contains(&poisson)) {
            return Err(Error::invalid("Poisson ratio", poisson, "0 <= nu <= 0.5"));
        }
        Ok(Self { youngs, poisson })
    }

    /// Plane-strain modulus E* = E/(1 − ν²).
    pub fn e_star(&self) -> f64 {
        self.youngs / (1.0 - self.poisson * self.poisson)
    }

    /// Shear modulus E/(2(1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.youngs / (2.0 * (1.0 + self.poisson))
    }
}

/// S, f and g at one value of q·d.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Response {
    pub s: f64,
    pub f: f64,
    pub g: f64,
}

/// A film (material 0) bonded to a substrate half-space (material 1): the d-independent part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bilayer {
    pub film: Elastic,
    pub substrate: Elastic,
}

impl Bilayer {
    pub fn new(film: Elastic, substrate: Elastic) -> Self {
        Self { film, substrate }
    }

    /// S(qd), eq. (7).
    pub fn s(&self, _qd: f64) -> f64 {
        todo!()
    }

    /// S, f and g at qd.
    pub fn response(&self, _qd: f64) -> Response {
        todo!()
    }
}

/// A film of given thickness (m) on its substrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stack {
    pub layers: Bilayer,
    pub thickness: f64,
}
