//! Run outputs: everything a run writes under `results/<case>/` (see `docs/outputs.md`).
//!
//! One concept per file:
//! - [`activity`]: which cells and points are active (excavation, placement);
//! - [`atomic`]: temp file + fsync + rename, so a crash never leaves a half-written file;
//! - [`field_data`]: named string arrays of a VTU (`region_names`);
//! - [`vtu`]: ParaView meshes with point and cell fields (XML UnstructuredGrid, raw binary);
//! - [`vtu_compressed`]: compact frames (Float32, zlib, a subset of the cells) for long runs;
//! - [`pvd`]: the time collection of the VTU files, rewritten after every step;
//! - [`histories`]: CSV time histories, buffered, resumable;
//! - [`summary`]: the end-of-run summary as pretty JSON.

pub mod activity;
pub mod atomic;
pub mod field_data;
pub mod histories;
pub mod pvd;
pub mod summary;
pub mod vtu;
pub mod vtu_compressed;

pub use atomic::{write_atomic, write_atomic_with};
pub use field_data::{read_string_arrays, VtuStrings};
pub use histories::HistoryWriter;
pub use pvd::{PvdCollection, PvdEntry};
pub use summary::write_summary;
pub use vtu::{write_vtu, write_vtu_lines, VtuField};
pub use vtu_compressed::{write_vtu_compressed, CellSubset, Precision};

/// The display form of a path used in error messages.
pub(crate) fn label(path: &std::path::Path) -> String {
    path.display().to_string()
}

/// A unique, empty scratch directory for tests (no extra dependency), removed with
/// everything in it when the test that made it ends, passed or failed.
#[cfg(test)]
pub(crate) struct TestDir(std::path::PathBuf);

#[cfg(test)]
impl std::ops::Deref for TestDir {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

#[cfg(test)]
impl Drop for TestDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A new [`TestDir`] named after `name`, the process and a counter.
#[cfg(test)]
pub(crate) fn test_dir(name: &str) -> TestDir {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static N: AtomicUsize = AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "dcfm-output-{name}-{}-{}",
        std::process::id(),
        N.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    TestDir(dir)
}
