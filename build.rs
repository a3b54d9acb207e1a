//! Compiles the CGAL bridge (src/reference/cgal/mod.rs + cpp/cgal_shim.cc) when the `cgal`
//! feature is on; without it there is nothing to build. Flags follow CGAL's requirements for
//! GCC: C++17, -frounding-math (the interval filters switch the rounding mode), and GMP for
//! the exact fallback of the Epick kernel.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    // The cfg compiles out the code that needs the optional cxx-build; the variable is how
    // Cargo tells a build script which features are on.
    if std::env::var_os("CARGO_FEATURE_CGAL").is_some() {
        #[cfg(feature = "cgal")]
        cgal::build();
    }
}

#[cfg(feature = "cgal")]
mod cgal {
    use std::path::Path;

    const BRIDGE: &str = "src/reference/cgal/mod.rs";
    const SOURCES: [&str; 2] = ["cpp/cgal_shim.cc", "cpp/cgal_shim.h"];

    pub fn build() {
        if !Path::new("/usr/include/CGAL/version.h").exists() {
            panic!(
                "CGAL headers not found: run `make deps` (installs Debian's libcgal-dev) or \
                 build with --no-default-features"
            );
        }
        // The C++ optimisation level follows the cargo profile: a debug-profile CGAL is many
        // times slower, so benchmarks must use the release profile.
        let opt_level = std::env::var("OPT_LEVEL").unwrap_or_else(|_| "2".to_string());
        cxx_build::bridge(BRIDGE)
            .file("cpp/cgal_shim.cc")
            .std("c++17")
            .flag("-frounding-math")
            .opt_level_str(&opt_level)
            .compile("hexmesh_cgal");
        println!("cargo:rustc-link-lib=gmp");
        println!("cargo:rerun-if-changed={BRIDGE}");
        for file in SOURCES {
            println!("cargo:rerun-if-changed={file}");
        }
    }
}
