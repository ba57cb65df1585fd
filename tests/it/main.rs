//! Integration tests: one binary, one module per area.
mod psd_read;
mod topography;
