//! Sets `cfg(loomkin_browser)` when Chromium and ChromeDriver are both installed, so that the
//! browser test is marked `ignored` (and counted so in the test summary) when they are not.

use std::path::PathBuf;

fn find(env: &str, names: &[&str], extra: &[&str]) -> bool {
    println!("cargo::rerun-if-env-changed={env}");
    if let Some(p) = std::env::var_os(env) {
        // An explicit path is used as given; the test reports it if it is wrong.
        return !p.is_empty();
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut found = std::env::split_paths(&path).any(|dir| names.iter().any(|n| dir.join(n).is_file()));
    found |= extra.iter().any(|p| PathBuf::from(p).is_file());
    // Watch only paths that exist: cargo takes a missing path as changed, so watching one would run
    // this script, and rebuild this crate and every crate above it, on every build. Installing a
    // program into /usr/bin later changes that directory, which runs the script again.
    for p in names.iter().map(|n| format!("/usr/bin/{n}")).chain(extra.iter().map(|p| p.to_string())) {
        if PathBuf::from(&p).exists() {
            println!("cargo::rerun-if-changed={p}");
        }
    }
    if PathBuf::from("/usr/bin").is_dir() {
        println!("cargo::rerun-if-changed=/usr/bin");
    }
    found
}

fn main() {
    println!("cargo::rustc-check-cfg=cfg(loomkin_browser)");
    println!("cargo::rerun-if-env-changed=PATH");
    println!("cargo::rerun-if-changed=build.rs");
    let chromium = find("LOOMKIN_CHROMIUM", &["chromium", "chromium-browser", "google-chrome"], &[]);
    let driver = find("LOOMKIN_CHROMEDRIVER", &["chromedriver"], &["/usr/lib/chromium/chromedriver"]);
    if chromium && driver {
        println!("cargo::rustc-cfg=loomkin_browser");
    }
}
