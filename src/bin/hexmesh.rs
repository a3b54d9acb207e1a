//! The `hexmesh` command; everything lives in `hexmesh::cli`.

fn main() -> std::process::ExitCode {
    hexmesh::cli::main()
}
