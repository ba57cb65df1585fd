//! The `coatcheck` command line: a thin layer over the library.
mod cli;

fn main() {
    keep_freed_memory();
    std::process::exit(cli::run());
}

/// glibc's malloc hands the top of the heap back to the kernel whenever 128 KiB are free there,
/// so the engine's per-evaluation buffers come back as fresh pages, with a system call and page
/// faults each time: a check with d_min on the 1000-point PSD made 309 `brk` calls and 690 page
/// faults, 1.2 ms of its 18 ms of CPU time. A command lives milliseconds: it keeps what it frees
/// until it exits (a trim threshold of 64 MiB), and takes blocks of up to 32 MiB from that heap
/// rather than from fresh mappings (glibc's own limits when it adapts them).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn keep_freed_memory() {
    const MIB: libc::c_int = 1 << 20;
    // SAFETY: `mallopt` only sets malloc parameters; no other thread exists yet. A value it
    // rejects leaves the default in place (return value 0), which is correct, only slower.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 32 * MIB);
        libc::mallopt(libc::M_TRIM_THRESHOLD, 64 * MIB);
    }
}

/// Other allocators keep their defaults.
#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn keep_freed_memory() {}
