//! Writes the input of one fuzz case as a Triangle .node file under `fuzz-failures/`, to
//! reproduce a case a campaign named: `cargo run --release --example fuzz_case SEED CASE`.

fn main() {
    let mut args = std::env::args().skip(1);
    let seed: u64 = args.next().and_then(|s| s.parse().ok()).expect("a seed");
    let case: u64 = args
        .next()
        .and_then(|s| s.parse().ok())
        .expect("a case number");
    let (family, input) = hexmesh::fuzz::generate_case(seed, case);
    match hexmesh::fuzz::write_failure(
        std::path::Path::new("fuzz-failures"),
        "hex",
        seed,
        case,
        family,
        &input,
    ) {
        Ok(path) => println!("{}", path.display()),
        Err(e) => eprintln!("cannot write the case: {e}"),
    }
}
