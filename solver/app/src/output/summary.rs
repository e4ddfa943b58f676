//! The end-of-run summary (`summary.json`): any serializable value as pretty JSON,
//! written atomically.

use std::io::Write;
use std::path::Path;

use serde::Serialize;

use super::atomic::write_atomic_with;

use dcfm::error::Result;

/// Write `value` to `path` as pretty-printed JSON (with a final newline), atomically.
pub fn write_summary<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    write_atomic_with(path, |w| {
        serde_json::to_writer_pretty(&mut *w, value).map_err(std::io::Error::other)?;
        w.write_all(b"\n")
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_dir;
    use std::collections::BTreeMap;

    #[derive(Serialize)]
    struct Summary {
        case: String,
        steps: u64,
        peak_damage: f64,
        energies: BTreeMap<String, f64>,
    }

    #[test]
    fn pretty_json_round_trip() {
        let dir = test_dir("summary");
        let path = dir.join("summary.json");
        let mut energies = BTreeMap::new();
        energies.insert("kinetic".to_string(), 1.25e6);
        energies.insert("internal".to_string(), 3.0e-7);
        let s = Summary {
            case: "yingxiuwan".into(),
            steps: 120_000,
            peak_damage: 0.875,
            energies,
        };
        write_summary(&path, &s).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(
            text.contains("\n  \"steps\": 120000,") && text.ends_with("}\n"),
            "{text}"
        );
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["energies"]["internal"], 3.0e-7);
        assert_eq!(v["case"], "yingxiuwan");
    }

    #[test]
    fn unserializable_value_keeps_the_old_file() {
        let dir = test_dir("summary-bad");
        let path = dir.join("summary.json");
        write_summary(&path, &[1, 2, 3]).unwrap();
        // A map with non-string keys cannot be JSON.
        let mut bad = BTreeMap::new();
        bad.insert((1, 2), 3.0);
        let msg = write_summary(&path, &bad).unwrap_err().to_string();
        assert!(msg.contains("summary.json"), "{msg}");
        assert_eq!(
            serde_json::from_str::<Vec<i32>>(&std::fs::read_to_string(&path).unwrap()).unwrap(),
            vec![1, 2, 3]
        );
    }
}
