//! scripts/slurm-shards.sbatch and scripts/slurm-submit.sh run without Slurm: the task script with
//! the variables Slurm sets, the submit script against a stand-in `sbatch` that records its calls.

use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).canonicalize().unwrap()
}

fn bin() -> PathBuf {
    assert_cmd::cargo::cargo_bin("loomkin")
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("loomkin-scripts-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const ARGS: [&str; 5] = ["law", "sample", "cycloidal", "--points", "40"];

/// One task as Slurm runs it: `sbatch --array=17 …` sets SLURM_ARRAY_TASK_ID = 17 and an array of
/// one task. On main the task took its index and count from that array and wrote the whole run
/// as part 1; here N is given, so the task remakes exactly part 17 of 20.
fn task(dir: &Path, id: u32, offset: u32, n: u32) -> std::process::Output {
    Command::new("bash")
        .arg(repo().join("scripts/slurm-shards.sbatch"))
        .arg(n.to_string())
        .arg(dir)
        .args(ARGS)
        .arg("--csv")
        .env("SLURM_ARRAY_TASK_ID", id.to_string())
        .env("SLURM_ARRAY_TASK_MIN", id.to_string())
        .env("SLURM_ARRAY_TASK_COUNT", "1")
        .env("LOOMKIN_SHARD_OFFSET", offset.to_string())
        .env("LOOMKIN", bin())
        .output()
        .unwrap()
}

#[test]
fn a_rerun_task_remakes_exactly_its_part() {
    let dir = tmp("task");
    let out = task(&dir, 17, 0, 20);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let part = dir.join("parts/part-00017-of-00020.csv");
    let shard = Command::new(bin()).args(ARGS).args(["--csv", "--shard", "17/20"]).output().unwrap().stdout;
    let text = std::fs::read(&part).unwrap();
    // The part is shard 17's rows after the header line.
    assert!(text.ends_with(&shard) && text.len() > shard.len(), "{}", String::from_utf8_lossy(&text));
    // Every other task (shards 1–8 in a first array, 9–20 through an offset of 8): the merge is the
    // one-machine output.
    for s in 1..=8 {
        assert!(task(&dir, s, 0, 20).status.success());
    }
    for s in 1..=12 {
        assert!(task(&dir, s, 8, 20).status.success());
    }
    let merged = Command::new(bin()).arg("merge").arg(dir.join("parts")).args(["-o", "-"]).output().unwrap();
    assert!(merged.status.success(), "{}", String::from_utf8_lossy(&merged.stderr));
    let whole = Command::new(bin()).args(ARGS).arg("--csv").output().unwrap().stdout;
    assert_eq!(merged.stdout, whole);
    // A task outside 1…N is refused rather than run.
    assert_eq!(task(&dir, 21, 0, 20).status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The submit script: the logs directory exists before the first `sbatch` (on main the
/// hand-written recipe's `--output=shards/…` failed every task), the shards split into arrays
/// below MaxArraySize with offsets, the options reach every array, and the merge waits with
/// `afterany` + `--kill-on-invalid-dep=yes` (on main `afterok` waited forever after a failure).
#[test]
fn submit_splits_past_max_array_size_and_merges_after_any() {
    let dir = tmp("submit");
    let record = dir.join("calls");
    let fake = dir.join("sbatch");
    std::fs::write(
        &fake,
        format!(
            "#!/bin/bash\nn=$(($(wc -l < {rec} 2>/dev/null || echo 0) + 1))\n\
             [ -d {study}/logs ] && logs=yes || logs=no\necho \"logs=$logs $*\" >> {rec}\necho \"$n;cluster\"\n",
            rec = record.display(),
            study = dir.join("study").display()
        ),
    )
    .unwrap();
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&fake, std::fs::Permissions::from_mode(0o755)).unwrap();
    let out = Command::new("bash")
        .arg(repo().join("scripts/slurm-submit.sh"))
        .args(["-n", "2500", "-c", "4", "--mem", "2G", "-t", "00:10:00", "-p", "short", "--throttle", "50"])
        .args(["--max-array", "1001"])
        .arg(dir.join("study"))
        .arg(dir.join("out.csv"))
        .args(ARGS)
        .arg("--csv")
        .env("SBATCH", &fake)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let calls = std::fs::read_to_string(&record).unwrap();
    let calls: Vec<&str> = calls.lines().collect();
    assert_eq!(calls.len(), 4, "{calls:#?}");
    for (call, (offset, spec)) in calls.iter().zip([(0, "1-1000%50"), (1000, "1-1000%50"), (2000, "1-500%50")]) {
        assert!(call.starts_with("logs=yes "), "{call}");
        for want in [
            format!("--array={spec}"),
            format!("LOOMKIN_SHARD_OFFSET={offset}"),
            "--cpus-per-task=4".into(),
            "--mem=2G".into(),
            "--time=00:10:00".into(),
            "--partition=short".into(),
            " 2500 ".into(),
        ] {
            assert!(call.contains(&want), "{want} not in {call}");
        }
    }
    let merge = calls[3];
    assert!(merge.contains("--dependency=afterany:1:2:3") && merge.contains("--kill-on-invalid-dep=yes"), "{merge}");
    assert!(merge.contains("merge") && merge.contains("out.csv"), "{merge}");
    std::fs::remove_dir_all(&dir).unwrap();
}
