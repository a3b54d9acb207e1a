//! Writes the input of one fuzz case under `fuzz-failures/`, to reproduce a case a campaign
//! named: `cargo run --release --example fuzz_case SEED CASE` writes the point set as a
//! Triangle .node file, `... SEED CASE domains` the domain of `fuzz --domains` as a .poly file.

fn main() {
    let mut args = std::env::args().skip(1);
    let seed: u64 = args.next().and_then(|s| s.parse().ok()).expect("a seed");
    let case: u64 = args
        .next()
        .and_then(|s| s.parse().ok())
        .expect("a case number");
    let dir = std::path::Path::new("fuzz-failures");
    let written = if args.next().as_deref() == Some("domains") {
        let c = hexmesh::fuzz_domains::generate_case(seed, case);
        hexmesh::fuzz_domains::write_failure(dir, "hex", seed, case, c.family, &c.input)
            .map_err(|e| e.to_string())
    } else {
        let (family, input) = hexmesh::fuzz::generate_case(seed, case);
        hexmesh::fuzz::write_failure(dir, "hex", seed, case, family, &input)
            .map_err(|e| e.to_string())
    };
    match written {
        Ok(path) => println!("{}", path.display()),
        Err(e) => eprintln!("cannot write the case: {e}"),
    }
}
