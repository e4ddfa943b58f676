//! The ParaView time collection (`case.pvd`): one `DataSet` per output step, mapping the
//! time to the VTU file (relative to the `.pvd`'s directory).
//!
//! The collection is rewritten atomically after every added step, so a run that crashes
//! still leaves a valid `.pvd` listing every VTU written before the crash. A resumed run
//! loads the existing collection ([`PvdCollection::resume`]), drops the steps after its
//! restart time ([`PvdCollection::truncate_after`]) and appends.

use std::path::{Path, PathBuf};

use super::{atomic::write_atomic, label, vtu::xml_escape};
use dcfm::error::{DcfmError, Result};

/// One step of the collection.
#[derive(Clone, Debug, PartialEq)]
pub struct PvdEntry {
    /// Time (s).
    pub time: f64,
    /// File name relative to the directory of the `.pvd`.
    pub file: String,
}

/// A `.pvd` collection kept on disk.
#[derive(Clone, Debug)]
pub struct PvdCollection {
    path: PathBuf,
    entries: Vec<PvdEntry>,
}

impl PvdCollection {
    /// Start a new, empty collection at `path` (written at once, replacing any old one).
    pub fn create(path: &Path) -> Result<Self> {
        let c = Self {
            path: path.to_path_buf(),
            entries: Vec::new(),
        };
        c.write()?;
        Ok(c)
    }

    /// Load an existing collection written by [`PvdCollection`].
    pub fn load(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path).map_err(|e| DcfmError::io(label(path), e))?;
        let entries = parse(&text).map_err(|message| DcfmError::Parse {
            file: label(path),
            message,
        })?;
        Ok(Self {
            path: path.to_path_buf(),
            entries,
        })
    }

    /// Load the collection if `path` exists, else create an empty one.
    pub fn resume(path: &Path) -> Result<Self> {
        if path.exists() {
            Self::load(path)
        } else {
            Self::create(path)
        }
    }

    /// Add a step and rewrite the file. Times must increase strictly (ParaView sorts by
    /// time and cannot tell two files with one time apart).
    pub fn add(&mut self, time: f64, file: &str) -> Result<()> {
        if !time.is_finite() {
            return Err(DcfmError::invalid(
                label(&self.path),
                "timestep",
                time,
                "a finite time",
            ));
        }
        if let Some(last) = self.entries.last() {
            if time <= last.time {
                return Err(DcfmError::invalid(
                    label(&self.path),
                    "timestep",
                    time,
                    format!(
                        "greater than the last time in the collection, {}",
                        last.time
                    ),
                ));
            }
        }
        self.entries.push(PvdEntry {
            time,
            file: file.to_string(),
        });
        self.write()
    }

    /// Drop the steps later than `time` (a run resumed from a checkpoint at `time`
    /// rewrites them) and rewrite the file.
    pub fn truncate_after(&mut self, time: f64) -> Result<()> {
        self.entries.retain(|e| e.time <= time);
        self.write()
    }

    /// Keep the steps for which `keep` holds and rewrite the file.
    pub fn retain(&mut self, keep: impl FnMut(&PvdEntry) -> bool) -> Result<()> {
        self.entries.retain(keep);
        self.write()
    }

    /// The steps, in time order.
    pub fn entries(&self) -> &[PvdEntry] {
        &self.entries
    }

    /// Where the collection lives.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn write(&self) -> Result<()> {
        write_atomic(&self.path, render(&self.entries).as_bytes())
    }
}

/// The XML text. Times use Rust's shortest round-trip form, so load(write(x)) == x.
fn render(entries: &[PvdEntry]) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
    );
    for e in entries {
        s.push_str(&format!(
            "    <DataSet timestep=\"{:?}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
            e.time,
            xml_escape(&e.file)
        ));
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    s
}

/// Parse the `DataSet` elements of a collection (the subset of XML that [`render`] and
/// ParaView write: one element per tag, double-quoted attributes).
fn parse(text: &str) -> std::result::Result<Vec<PvdEntry>, String> {
    if !text.contains("type=\"Collection\"") {
        return Err("not a VTK Collection file (no type=\"Collection\")".into());
    }
    let mut out = Vec::new();
    for (i, chunk) in text.split("<DataSet").skip(1).enumerate() {
        let tag = chunk
            .split_once('>')
            .map(|(t, _)| t)
            .ok_or_else(|| format!("DataSet {i}: unterminated tag"))?;
        let attr = |name: &str| -> std::result::Result<String, String> {
            let key = format!(" {name}=\"");
            let start = tag
                .find(&key)
                .ok_or_else(|| format!("DataSet {i}: no {name} attribute"))?
                + key.len();
            let end = tag[start..]
                .find('"')
                .ok_or_else(|| format!("DataSet {i}: unterminated {name} attribute"))?;
            Ok(xml_unescape(&tag[start..start + end]))
        };
        let t = attr("timestep")?;
        let time: f64 = t
            .trim()
            .parse()
            .map_err(|_| format!("DataSet {i}: timestep = {t}: not a number"))?;
        out.push(PvdEntry {
            time,
            file: attr("file")?,
        });
    }
    out.sort_by(|a, b| a.time.total_cmp(&b.time));
    Ok(out)
}

fn xml_unescape(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_dir;

    #[test]
    fn every_add_leaves_a_valid_file() {
        let dir = test_dir("pvd");
        let path = dir.join("case.pvd");
        let mut c = PvdCollection::create(&path).unwrap();
        assert!(PvdCollection::load(&path).unwrap().entries().is_empty());
        c.add(0.0, "mesh_000000.vtu").unwrap();
        c.add(0.1, "mesh_000010.vtu").unwrap();
        // A "crash" here: what is on disk is complete and readable.
        let on_disk = PvdCollection::load(&path).unwrap();
        assert_eq!(on_disk.entries(), c.entries());
        assert_eq!(on_disk.entries()[1].time, 0.1);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("timestep=\"0.1\"") && text.trim_end().ends_with("</VTKFile>"));
    }

    #[test]
    fn resume_truncate_and_append() {
        let dir = test_dir("pvd-resume");
        let path = dir.join("case.pvd");
        let mut c = PvdCollection::resume(&path).unwrap();
        for (i, t) in [0.0, 1e-3, 2e-3, 3e-3].iter().enumerate() {
            c.add(*t, &format!("mesh_{i:06}.vtu")).unwrap();
        }
        let mut r = PvdCollection::resume(&path).unwrap();
        assert_eq!(r.entries().len(), 4);
        r.truncate_after(2e-3).unwrap();
        r.add(2.5e-3, "mesh_&<odd>.vtu").unwrap();
        let back = PvdCollection::load(&path).unwrap();
        let times: Vec<f64> = back.entries().iter().map(|e| e.time).collect();
        assert_eq!(times, vec![0.0, 1e-3, 2e-3, 2.5e-3]);
        assert_eq!(back.entries()[3].file, "mesh_&<odd>.vtu");
    }

    #[test]
    fn times_must_increase_and_be_finite() {
        let dir = test_dir("pvd-order");
        let path = dir.join("case.pvd");
        let mut c = PvdCollection::create(&path).unwrap();
        c.add(1.0, "a.vtu").unwrap();
        let msg = c.add(1.0, "b.vtu").unwrap_err().to_string();
        assert!(msg.contains("case.pvd") && msg.contains("greater"), "{msg}");
        assert!(c.add(f64::NAN, "c.vtu").is_err());
        assert_eq!(PvdCollection::load(&path).unwrap().entries().len(), 1);
    }

    #[test]
    fn garbage_is_a_parse_error_naming_the_file() {
        let dir = test_dir("pvd-bad");
        let path = dir.join("broken.pvd");
        std::fs::write(
            &path,
            "<VTKFile type=\"Collection\"><DataSet timestep=\"x\" file=\"a\"/>",
        )
        .unwrap();
        let msg = PvdCollection::load(&path).unwrap_err().to_string();
        assert!(
            msg.contains("broken.pvd") && msg.contains("not a number"),
            "{msg}"
        );
        std::fs::write(&path, "hello").unwrap();
        assert!(PvdCollection::load(&path).is_err());
    }
}
