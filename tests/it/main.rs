//! Integration tests: one binary, one module per area.
mod check;
mod cli_check;
mod layer;
