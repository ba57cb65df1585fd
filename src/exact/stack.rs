//! The exact path of `check --verify` on a layer stack: the stress checks judged on the solved
//! fields at every interface ([`crate::verify_stack`]; under sliding friction on the total
//! fields, [`crate::verify_stack::sliding`]) and, when min-thickness is enabled, the
//! exact minimum thickness of the layer `criteria.thickness_of`
//! ([`super::stack_min_thickness`]), with its check added to the verification's checks and
//! verdict (the exact verdict of [`super`]).

use super::min_thickness::ExactMinThickness;
use super::stack_min_thickness;
use crate::bem::{BemSettings, Surface};
use crate::check::stack::StackDesign;
use crate::error::Error;
use crate::verify_stack::{self, StackVerification};

/// The exact check of a stack design on one surface under the sliding friction `mu` (0: static
/// contact): the stress checks at the design's thicknesses and, when min-thickness is enabled,
/// the exact d_min and its check.
pub fn on_stack_surface(
    surface: &Surface,
    design: &StackDesign,
    mu: f64,
    settings: &BemSettings,
) -> Result<(StackVerification, Option<ExactMinThickness>), Error> {
    let mut v = verify_stack::verify(surface, design, mu, settings)?;
    let m = design
        .criteria
        .checks
        .min_thickness
        .then(|| stack_min_thickness::min_thickness(surface, design, mu, settings))
        .transpose()?;
    if let Some(m) = &m {
        add_min_thickness(&mut v, design, m);
    }
    Ok((v, m))
}

/// The min-thickness check of `m` added to the verification's checks and verdict.
pub(crate) fn add_min_thickness(
    v: &mut StackVerification,
    design: &StackDesign,
    m: &ExactMinThickness,
) {
    let check = stack_min_thickness::check(design, m);
    v.pass &= check.check.pass;
    v.checks.push(check);
}
