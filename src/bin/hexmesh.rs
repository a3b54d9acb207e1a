//! The `hexmesh` command; everything lives in `hexmesh::cli`, except the hidden
//! `__run-mesher` subcommand of process isolation (`hexmesh::isolate`), dispatched first so
//! that a child never parses the public command line.

fn main() -> std::process::ExitCode {
    if std::env::args_os()
        .nth(1)
        .is_some_and(|a| a == hexmesh::isolate::CHILD_COMMAND)
    {
        return hexmesh::isolate::child_main();
    }
    hexmesh::cli::main()
}
