//! hexmesh, the harness: the `hexmesh` command, the reference meshers (CGAL through cxx,
//! Shewchuk's Triangle, spade), the datasets of the papers, the report (CSV, Table 1, plots,
//! pictures), isolated runs of meshers in child processes and the fuzz campaigns, around the
//! meshing library `hexmesh-core`.
//!
//! The library's modules are re-exported under their own names, so `hexmesh::quality` is
//! `hexmesh_core::quality` and `hexmesh::hex` is `hexmesh_core::internals::hex`. Data flow: [`Pslg`] → [`Mesher::mesh`] → [`MeshRun`] (a [`TriMesh`])
//! → `quality` → `report`.

pub use hexmesh_core::internals::{hex, refine, rhomb};
pub use hexmesh_core::{error, geom, io, mesh, progress, quality};

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

/// mimalloc's option `allow_thp` (`mi_option_allow_thp`, the 44th of that header's options).
const MI_OPTION_ALLOW_THP: libmimalloc_sys::mi_option_t = 43;

/// Sets up [`Allocator`] for meshing. Call it first thing in `main`; it is harmless to call
/// again. Each setting can be overridden from the environment (`MIMALLOC_PURGE_DELAY`,
/// `MIMALLOC_ALLOW_THP`), where mimalloc reads them itself.
///
/// - Freed memory goes back to the kernel at once instead of a second later: mimalloc's
///   default kept the freed tables of one phase while the next allocated its own, and
///   plane-100k's peak memory rose from 1.30 GB (glibc) to 1.63 GB, against 1.32 GB with this
///   setting.
/// - No transparent huge pages (on Linux, for the whole process and its children, with
///   `PR_SET_THP_DISABLE`; mimalloc asks for them on its arenas by default). Memory given back
///   at once and taken again is faulted in afresh, and with huge pages each such fault clears
///   2 MB: on this project's machines `hex` spent 40 % of its time at plane-10k in the kernel
///   clearing pages, and its meshing call at plane-100k took 35.6 s against 19.7 s without
///   them, with the same peak memory (`METHODOLOGY.md`, "Performance history").
pub fn configure_allocator() {
    if std::env::var_os("MIMALLOC_PURGE_DELAY").is_none() {
        // SAFETY: a plain store into mimalloc's table of options, which it reads when it
        // purges; the callers make it before they start threads.
        unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_PURGE_DELAY, PURGE_DELAY_MS) }
    }
    if std::env::var_os("MIMALLOC_ALLOW_THP").is_none() {
        // SAFETY: as above; mimalloc reads the option each time it maps an arena.
        unsafe { libmimalloc_sys::mi_option_set(MI_OPTION_ALLOW_THP, 0) }
        // The arenas mapped before `main` (the runtime's first allocations) were already
        // advised to use huge pages: the process-wide switch covers them too.
        #[cfg(target_os = "linux")]
        // SAFETY: a prctl that only sets a flag of this process; its result is not needed
        // (a kernel without THP has nothing to switch off).
        unsafe {
            libc::prctl(libc::PR_SET_THP_DISABLE, 1, 0, 0, 0);
        }
    }
}

#[cfg(test)]
mod tests {
    /// One test for both options: `configure_allocator` changes process-wide state that a
    /// second test running beside it would see.
    #[test]
    fn the_allocator_options_are_the_ones_mimalloc_documents_and_the_environment_overrides_them() {
        // SAFETY: reads one option (`configure_allocator`: no other test writes it).
        let get = |option| unsafe { libmimalloc_sys::mi_option_get(option) };
        let (delay, thp) = (super::MI_OPTION_PURGE_DELAY, super::MI_OPTION_ALLOW_THP);
        let from_env = |name| {
            std::env::var(name)
                .ok()
                .map(|v: String| v.trim().parse::<std::ffi::c_long>().ok())
        };
        let (delay_env, thp_env) = (
            from_env("MIMALLOC_PURGE_DELAY"),
            from_env("MIMALLOC_ALLOW_THP"),
        );
        // mimalloc v3.3's defaults: 1000 ms, and huge pages allowed on Linux; another index
        // reads another option.
        if delay_env.is_none() {
            assert_eq!(get(delay), 1000);
        }
        #[cfg(target_os = "linux")]
        if thp_env.is_none() {
            assert_eq!(get(thp), 1);
        }
        super::configure_allocator();
        // A value given in the environment is mimalloc's to read (one that does not parse is
        // not checked here).
        match delay_env {
            None => assert_eq!(get(delay), super::PURGE_DELAY_MS),
            Some(given) => assert!(given.is_none_or(|d| d == get(delay))),
        }
        if let Some(given) = thp_env {
            assert!(given.is_none_or(|t| t == get(thp)));
        } else {
            assert_eq!(get(thp), 0);
            // SAFETY: reads this process's flag.
            #[cfg(target_os = "linux")]
            assert_eq!(
                unsafe { libc::prctl(libc::PR_GET_THP_DISABLE, 0, 0, 0, 0) },
                1
            );
        }
    }
}
