//! Helpers shared by the topic modules: run the binary, read its JSON, expect a usage error.

use assert_cmd::Command;
use serde_json::Value;

/// The `loomkin` binary under test.
pub fn loomkin() -> Command {
    Command::cargo_bin("loomkin").unwrap()
}

/// Runs, expects success, parses stdout as JSON.
pub fn stdout_json(args: &[&str]) -> Value {
    let out = loomkin().args(args).output().unwrap();
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Runs, expects exit code 2 and exactly one line on stderr containing every `needle`, nothing on stdout.
pub fn usage_error(args: &[&str], needles: &[&str]) {
    let out = loomkin().args(args).output().unwrap();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    let err = String::from_utf8_lossy(&out.stderr);
    for n in needles {
        assert!(err.contains(n), "{args:?}: stderr lacks '{n}': {err}");
    }
    assert!(!err.contains("panicked") && !err.contains("NaN"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: not one line: {err}");
    assert!(out.stdout.is_empty(), "{args:?}: wrote to stdout");
}
