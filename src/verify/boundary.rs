//! The boundary of the exact solve on a height map: periodic (the map is one period) or free
//! (the map is a window of a larger surface, [`crate::bem::free`]), given or chosen by the
//! periodicity test on the map's edges.
//!
//! The test is the edge mismatch of [`crate::topography::plausible`]: the rms height step
//! across the map's edges (last column to first, last row to first) over the rms step between
//! interior neighbours, along both axes together. On a periodic map the steps across the edges
//! are neighbour steps like the others and the ratio is about 1; on a map cut from a larger
//! surface they are of the order of h_rms. `auto` solves with free boundaries when the ratio
//! exceeds [`EDGE_MISMATCH_WARN`] (the level above which the map's spectrum is also reported
//! as not periodic), periodic otherwise.

use crate::bem::Boundary;
use crate::topography::HeightMap;
use crate::topography::plausible::{EDGE_MISMATCH_WARN, edge_mismatch_map};
use serde_json::{Value, json};

/// The boundary asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BoundaryChoice {
    /// By the periodicity test.
    #[default]
    Auto,
    Periodic,
    Free,
}

impl BoundaryChoice {
    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::Periodic => "periodic",
            Self::Free => "free",
        }
    }
}

/// The boundary used and why.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundaryDecision {
    pub boundary: Boundary,
    pub choice: BoundaryChoice,
    /// The periodicity test's ratio (none for synthesised, periodic surfaces).
    pub edge_mismatch: Option<f64>,
}

impl BoundaryDecision {
    /// The boundary for `map` under `choice`.
    pub fn for_map(choice: BoundaryChoice, map: &HeightMap) -> Self {
        Self::from_ratio(choice, edge_mismatch_map(map))
    }

    /// The boundary under `choice` for a map of edge mismatch `ratio` ([`edge_mismatch_map`]).
    pub fn from_ratio(choice: BoundaryChoice, ratio: f64) -> Self {
        let boundary = match choice {
            BoundaryChoice::Periodic => Boundary::Periodic,
            BoundaryChoice::Free => Boundary::Free,
            BoundaryChoice::Auto if ratio > EDGE_MISMATCH_WARN => Boundary::Free,
            BoundaryChoice::Auto => Boundary::Periodic,
        };
        Self {
            boundary,
            choice,
            edge_mismatch: Some(ratio),
        }
    }

    /// The boundary for surfaces synthesised periodic: periodic unless free was asked for.
    pub fn synthesised(choice: BoundaryChoice) -> Self {
        Self {
            boundary: match choice {
                BoundaryChoice::Free => Boundary::Free,
                _ => Boundary::Periodic,
            },
            choice,
            edge_mismatch: None,
        }
    }

    /// One line for a table, e.g. `free (auto: edge steps 7.31 x the interior's, above 3)`.
    pub fn describe(&self) -> String {
        let test = match (self.choice, self.edge_mismatch) {
            (BoundaryChoice::Auto, Some(r)) => format!(
                "auto: rms edge step {r:.3} x the interior's, {} {EDGE_MISMATCH_WARN}",
                if self.boundary == Boundary::Free {
                    "above"
                } else {
                    "at most"
                }
            ),
            (BoundaryChoice::Auto, None) => "auto: synthesised periodic surface".into(),
            (c, Some(r)) => format!(
                "--boundary {}; rms edge step {r:.3} x the interior's",
                c.name()
            ),
            (c, None) => format!("--boundary {}", c.name()),
        };
        format!("{} ({test})", self.boundary.name())
    }

    /// The JSON object `boundary`.
    pub fn json(&self) -> Value {
        json!({
            "kind": self.boundary.name(),
            "choice": self.choice.name(),
            "edge_mismatch": self.edge_mismatch,
            "auto_free_above": EDGE_MISMATCH_WARN,
        })
    }
}
