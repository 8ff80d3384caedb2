//! Tells the bench which Cargo profile built it, so that its report can
//! state it (`[profile.peers]`: fat LTO, one codegen unit).

fn main() {
    // OUT_DIR is TARGET/[TRIPLE/]PROFILE/build/PACKAGE-HASH/out.
    let out = std::env::var("OUT_DIR").unwrap_or_default();
    let profile = std::path::Path::new(&out)
        .ancestors()
        .nth(3)
        .and_then(|p| p.file_name())
        .map_or_else(|| "unknown".into(), |p| p.to_string_lossy().into_owned());
    let opt = std::env::var("OPT_LEVEL").unwrap_or_else(|_| "unknown".into());
    println!("cargo:rustc-env=ZLINE_BENCH_PROFILE={profile}");
    println!("cargo:rustc-env=ZLINE_BENCH_OPT_LEVEL={opt}");
    println!("cargo:rerun-if-changed=build.rs");
}
