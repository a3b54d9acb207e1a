//! The `hexmesh` command; everything lives in `hexmesh::cli`, except the hidden
//! `__run-mesher` subcommand of process isolation (`hexmesh::isolate`), dispatched first so
//! that a child never parses the public command line.
//!
//! Its allocations go through mimalloc (`hexmesh::Allocator`, where the reason is).

#[global_allocator]
static ALLOCATOR: hexmesh::Allocator = hexmesh::Allocator;

fn main() -> std::process::ExitCode {
    hexmesh::configure_allocator();
    // A reader that stops early (`hexmesh verify … | head`) ends the command quietly, as it
    // ends other command-line tools, instead of a panic on the next write: Rust ignores
    // SIGPIPE unless told otherwise.
    #[cfg(unix)]
    // SAFETY: restoring the default disposition of one signal, before any thread starts.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    if std::env::args_os()
        .nth(1)
        .is_some_and(|a| a == hexmesh::isolate::CHILD_COMMAND)
    {
        return hexmesh::isolate::child_main();
    }
    hexmesh::cli::main()
}
