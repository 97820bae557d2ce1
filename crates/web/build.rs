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
    for n in names {
        // Installing the program later (same PATH) runs this script again.
        println!("cargo::rerun-if-changed=/usr/bin/{n}");
    }
    for p in extra {
        println!("cargo::rerun-if-changed={p}");
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
