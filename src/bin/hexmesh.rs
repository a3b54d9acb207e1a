//! The `hexmesh` command line. For now only the hidden `__run-mesher` subcommand of process
//! isolation (`hexmesh::isolate`) is wired; the full CLI of DESIGN.md replaces this main and
//! keeps that dispatch.

use std::process::ExitCode;

fn main() -> ExitCode {
    if std::env::args_os()
        .nth(1)
        .is_some_and(|a| a == hexmesh::isolate::CHILD_COMMAND)
    {
        return hexmesh::isolate::child_main();
    }
    eprintln!("hexmesh: CLI not wired yet");
    ExitCode::FAILURE
}
