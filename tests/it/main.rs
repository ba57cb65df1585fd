//! Integration tests: one binary, one module per area.
mod batch;
mod bem;
mod check;
mod cli_check;
mod cli_psd_format;
mod cli_response;
mod common;
mod contact;
mod extreme;
mod figures;
mod fuzz;
mod layer;
mod psd_convert;
mod psd_read;
mod topography;
mod validity;
mod verify_check;
