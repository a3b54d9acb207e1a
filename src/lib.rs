//! hexmesh, the harness: the `hexmesh` command, the reference meshers (CGAL through cxx,
//! Shewchuk's Triangle, spade), the datasets of the papers, the report (CSV, Table 1, plots,
//! pictures), isolated runs of meshers in child processes and the fuzz campaigns, around the
//! meshing library `hexmesh-core`.
//!
//! The library's modules are re-exported under their own names, so `hexmesh::quality` is
//! `hexmesh_core::quality` and `hexmesh::hex` is `hexmesh_core::internals::hex`. Data flow: [`Pslg`] → [`Mesher::mesh`] → [`MeshRun`] (a [`TriMesh`])
//! → `quality` → `report`.

pub use hexmesh_core::internals::{hex, refine, rhomb};
pub use hexmesh_core::{error, geom, io, mesh, quality};

/// The library's `mesher` module (`hexmesh_core::mesher`): the trait every mesher sits
/// behind, its parameters and its result. (A plain re-export would bring the library's
/// function `mesher` too, which `registry::mesher` replaces here.)
pub mod mesher {
    pub use hexmesh_core::mesher::*;
}

pub mod cli;
pub mod datasets;
pub mod fuzz;
pub mod fuzz_domains;
pub mod isolate;
pub mod maxangle;
pub mod reference;
pub mod registry;
pub mod report;

pub use error::{Error, InputError, Result, Unenclosed};
pub use geom::{Hexagon, Point};
pub use mesh::{Labels, Pslg, Region, TriMesh};
pub use mesher::{Budget, MeshRun, Mesher, Params, StopReason};
pub use registry::{mesher, mesher_names, meshers};

/// The allocator the `hexmesh` command, the benches and the timing examples declare as their
/// global allocator (a library leaves that choice to its user); they call
/// [`configure_allocator`] first. Measured against glibc's `malloc` on one machine (README,
/// "Times"): plane-1m 384 s against 472 s and plane-100k 29 s against 33 s, with the same
/// peak memory; plane-10k about 15 % slower; plane-1k and plane-2k within the drift.
pub use mimalloc::MiMalloc as Allocator;

/// mimalloc's option `purge_delay` (`mi_option_purge_delay` in the `mimalloc.h` of the v3.3 that
/// libmimalloc-sys 0.1.49 builds), which the sys crate names no constant for.
const MI_OPTION_PURGE_DELAY: libmimalloc_sys::mi_option_t = 15;

/// The purge delay [`configure_allocator`] sets, in milliseconds.
const PURGE_DELAY_MS: std::ffi::c_long = 0;

/// Sets [`Allocator`] to give freed memory back to the kernel at once instead of a second later:
/// its default kept the freed tables of one phase while the next allocated its own, and
/// plane-100k's peak memory rose from 1.30 GB (glibc) to 1.63 GB, against 1.32 GB with this
/// setting. Call it first thing in `main`; it is harmless to call again.
pub fn configure_allocator() {
    // mimalloc reads its options from the environment too: a delay given there is kept.
    if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
        // SAFETY: a plain store into mimalloc's table of options, which it reads when it
        // purges; the callers make it before they start threads.
        unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, PURGE_DELAY_MS) }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_purge_delay_option_is_the_one_mimalloc_documents_and_the_environment_overrides_it() {
        // SAFETY: reads one option (`configure_allocator`: no other test writes it).
        let get = || unsafe { libmimalloc_sys::mi_option_get(super::MI_OPTION_PURGE_DELAY) };
        match std::env::var("MIMALLOC_PURGE_DELAY").ok() {
            None => {
                // mimalloc v3.3's default is 1000 ms; another index reads another option.
                assert_eq!(get(), 1000);
                super::configure_allocator();
                assert_eq!(get(), super::PURGE_DELAY_MS);
            }
            Some(delay) => {
                super::configure_allocator();
                assert_eq!(Some(get()), delay.trim().parse().ok());
            }
        }
    }
}
