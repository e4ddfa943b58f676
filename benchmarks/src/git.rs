//! The commit a measurement belongs to.

use std::path::Path;
use std::process::Command;

/// Path of the history file relative to the repository root; appending to it must not make
/// the next measurement look dirty.
const HISTORY_PATHSPEC: &str = ":(exclude)benchmarks/history.jsonl";

/// `git rev-parse --short HEAD` run in `root`, with `-dirty` appended when tracked or
/// untracked files differ from HEAD (the history file excepted); `unknown` without git.
pub fn commit_label(root: &Path) -> String {
    let Some(hash) = git(root, &["rev-parse", "--short", "HEAD"]) else {
        return "unknown".to_string();
    };
    let hash = hash.trim().to_string();
    if hash.is_empty() {
        return "unknown".to_string();
    }
    match git(
        root,
        &["status", "--porcelain", "--", ".", HISTORY_PATHSPEC],
    ) {
        Some(status) if !status.trim().is_empty() => format!("{hash}-dirty"),
        _ => hash,
    }
}

/// Stdout of a successful git command, `None` on any failure.
fn git(root: &Path, args: &[&str]) -> Option<String> {
    let out = Command::new("git")
        .args(args)
        .current_dir(root)
        .output()
        .ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).into_owned())
}
