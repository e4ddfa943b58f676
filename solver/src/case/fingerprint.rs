//! What a checkpoint was written for: a hash of every field of the case file and a hash
//! of the mesh content, so that a resume can refuse a checkpoint of another case and say
//! which fields changed (docs/outputs.md, "Checkpoints").
//!
//! The case is hashed field by field, from the parsed TOML rather than the text: comments,
//! blank lines, key order and number spelling (`1e9` or `1000000000.0`) do not count; the
//! values do. Each leaf gets its dotted path (`interfaces[0].mu_s`, `damping.alpha`); an
//! array holding tables is indexed, an array of numbers or strings is one leaf. Three
//! fields are left out because a resumed run may change them: `title`, `time.end` (run
//! further than the interrupted run meant to) and `time.max_steps` (its step budget).
//! The mesh is hashed from what the solver uses — coordinates (bit patterns), connectivity,
//! element regions and their names, node, element and face sets — so an edited Gmsh file,
//! or a generator whose output changed, is seen even when the case text is the same.
//! Likewise every ground motion is hashed from the samples the solver uses (after reading
//! and processing), under the pseudo-field `motions.NAME (record)`: an edited record file
//! — same path, other content — is refused on resume like an edited mesh (issue 13.5).

use std::collections::BTreeMap;

use crate::fnv::Fnv64;
use crate::mesh::Mesh;

/// Suffix of the pseudo-field that holds the hash of a ground motion's samples.
const RECORD: &str = " (record)";

/// Fields of the case that a resumed run may change.
const NOT_HASHED: [&str; 3] = ["title", "time.end", "time.max_steps"];

/// The hashes of a case file's fields and of its mesh.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CaseFingerprint {
    /// Dotted path of every leaf field → hash of its value.
    pub fields: BTreeMap<String, u64>,
    /// Hash of the mesh content.
    pub mesh: u64,
}

impl CaseFingerprint {
    /// The fingerprint of the case `text` (valid TOML) built into `mesh`.
    pub fn new(text: &str, mesh: &Mesh) -> Result<Self, String> {
        let table: toml::Table = text.parse().map_err(|e: toml::de::Error| e.to_string())?;
        let mut fields = BTreeMap::new();
        flatten_table(&table, "", &mut fields);
        for p in NOT_HASHED {
            fields.remove(p);
        }
        Ok(CaseFingerprint {
            fields,
            mesh: mesh_hash(mesh),
        })
    }

    /// Add the hash of every ground motion the case uses, from its processed samples
    /// (step, and each component's name, axis, acceleration, velocity and displacement),
    /// as the pseudo-field `motions.NAME (record)`.
    pub fn add_motions(&mut self, motions: &crate::motion::Motions) {
        for (name, m) in motions {
            let mut h = Fnv64::new();
            h.u64(m.dt.to_bits());
            h.u64(m.components.len() as u64);
            for c in &m.components {
                h.str(&c.name);
                h.str(&format!("{:?}", c.axis));
                h.u64(c.dt.to_bits());
                for series in [&c.acceleration, &c.velocity, &c.displacement] {
                    h.u64(series.len() as u64);
                    for x in series.iter() {
                        h.u64(x.to_bits());
                    }
                }
            }
            self.fields
                .insert(format!("motions.{name}{RECORD}"), h.finish());
        }
    }

    /// What differs from `earlier` (the fingerprint a checkpoint was written with) to
    /// `self` (the case now): one line per changed, added or removed field, then the mesh.
    pub fn changes_since(&self, earlier: &CaseFingerprint) -> Vec<String> {
        let mut out = Vec::new();
        for (path, h) in &earlier.fields {
            match self.fields.get(path) {
                Some(now) if now == h => {}
                Some(_) => match path
                    .strip_suffix(RECORD)
                    .map(|m| m.strip_prefix("motions.").unwrap_or(m))
                {
                    Some(m) => out.push(format!(
                        "the record of ground motion {m} changed (its file's content or its \
                         processing)"
                    )),
                    None => out.push(format!("case field {path} changed")),
                },
                None => out.push(format!("case field {path} removed")),
            }
        }
        for path in self.fields.keys() {
            if !earlier.fields.contains_key(path) {
                out.push(format!("case field {path} added"));
            }
        }
        if self.mesh != earlier.mesh {
            out.push("the mesh changed (coordinates, connectivity, regions or sets)".to_string());
        }
        out
    }

    /// Little-endian bytes: the number of fields, each as (path length, path, hash), then
    /// the mesh hash.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut b = Vec::new();
        b.extend((self.fields.len() as u64).to_le_bytes());
        for (path, h) in &self.fields {
            b.extend((path.len() as u64).to_le_bytes());
            b.extend(path.as_bytes());
            b.extend(h.to_le_bytes());
        }
        b.extend(self.mesh.to_le_bytes());
        b
    }

    /// Read what [`CaseFingerprint::to_bytes`] wrote at the start of `bytes`; the
    /// fingerprint and the number of bytes it took, or None when the bytes are not one.
    pub fn from_bytes(bytes: &[u8]) -> Option<(Self, usize)> {
        let mut pos = 0usize;
        let u64_at = |pos: &mut usize| -> Option<u64> {
            let s = bytes.get(*pos..pos.checked_add(8)?)?;
            *pos += 8;
            Some(u64::from_le_bytes(s.try_into().ok()?))
        };
        let n = u64_at(&mut pos)?;
        let mut fields = BTreeMap::new();
        for _ in 0..n {
            let len = usize::try_from(u64_at(&mut pos)?).ok()?;
            let path = bytes.get(pos..pos.checked_add(len)?)?;
            pos += len;
            let path = std::str::from_utf8(path).ok()?.to_string();
            fields.insert(path, u64_at(&mut pos)?);
        }
        let mesh = u64_at(&mut pos)?;
        Some((CaseFingerprint { fields, mesh }, pos))
    }
}

fn flatten_table(t: &toml::Table, prefix: &str, out: &mut BTreeMap<String, u64>) {
    if t.is_empty() && !prefix.is_empty() {
        // An empty section still says something (`[static]` with its defaults).
        out.insert(prefix.to_string(), Fnv64::new().finish());
    }
    for (k, v) in t {
        let path = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        flatten_value(v, path, out);
    }
}

fn flatten_value(v: &toml::Value, path: String, out: &mut BTreeMap<String, u64>) {
    match v {
        toml::Value::Table(t) => flatten_table(t, &path, out),
        toml::Value::Array(a) if a.iter().any(|x| x.is_table() || x.is_array()) => {
            if a.is_empty() {
                out.insert(path, leaf_hash(v));
                return;
            }
            for (i, x) in a.iter().enumerate() {
                flatten_value(x, format!("{path}[{i}]"), out);
            }
        }
        _ => {
            out.insert(path, leaf_hash(v));
        }
    }
}

fn leaf_hash(v: &toml::Value) -> u64 {
    let mut h = Fnv64::new();
    hash_value(v, &mut h);
    h.finish()
}

/// A canonical hash of a value: a type tag, then the content (floats by their bits,
/// tables with their keys in sorted order).
fn hash_value(v: &toml::Value, h: &mut Fnv64) {
    match v {
        toml::Value::String(s) => {
            h.update(b"s");
            h.str(s);
        }
        toml::Value::Integer(i) => {
            h.update(b"i");
            h.u64(*i as u64);
        }
        toml::Value::Float(x) => {
            h.update(b"f");
            h.u64(x.to_bits());
        }
        toml::Value::Boolean(b) => {
            h.update(if *b { b"T" } else { b"F" });
        }
        toml::Value::Datetime(d) => {
            h.update(b"d");
            h.str(&d.to_string());
        }
        toml::Value::Array(a) => {
            h.update(b"a");
            h.u64(a.len() as u64);
            for x in a {
                hash_value(x, h);
            }
        }
        toml::Value::Table(t) => {
            h.update(b"t");
            let keys: std::collections::BTreeSet<&String> = t.keys().collect();
            h.u64(keys.len() as u64);
            for k in keys {
                h.str(k);
                hash_value(&t[k.as_str()], h);
            }
        }
    }
}

/// Hash of what the solver takes from a mesh.
pub fn mesh_hash(mesh: &Mesh) -> u64 {
    let mut h = Fnv64::new();
    h.u64(mesh.coords.len() as u64);
    for x in &mesh.coords {
        for c in x {
            h.u64(c.to_bits());
        }
    }
    h.u64(mesh.elements.len() as u64);
    for e in &mesh.elements {
        for n in e {
            h.update(&n.to_le_bytes());
        }
    }
    for r in &mesh.element_region {
        h.update(&r.to_le_bytes());
    }
    h.u64(mesh.region_names.len() as u64);
    for name in &mesh.region_names {
        h.str(name);
    }
    for (sets, tag) in [(&mesh.node_sets, b"N"), (&mesh.element_sets, b"E")] {
        h.update(tag);
        h.u64(sets.len() as u64);
        for (name, members) in sets {
            h.str(name);
            h.u64(members.len() as u64);
            for m in members {
                h.update(&m.to_le_bytes());
            }
        }
    }
    h.update(b"F");
    h.u64(mesh.face_sets.len() as u64);
    for (name, faces) in &mesh.face_sets {
        h.str(name);
        h.u64(faces.len() as u64);
        for f in faces {
            h.update(&f.element.to_le_bytes());
            h.update(&[f.local]);
        }
    }
    h.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fp(text: &str) -> CaseFingerprint {
        CaseFingerprint::new(text, &Mesh::default()).unwrap()
    }

    const CASE: &str = r#"
title = "a"
[time]
end = 1.0
dt = 1e-4
[[interfaces]]
name = "j"
mu_s = 0.6
[[interfaces]]
name = "k"
mu_s = 0.5
"#;

    #[test]
    fn layout_comments_and_number_spelling_do_not_count() {
        let other = "# a comment\n[[interfaces]]\nmu_s = 0.6\nname = \"j\"\n\
                     [[interfaces]]\nname = \"k\"\nmu_s = 5e-1\n[time]\ndt = 0.0001\nend = 1.0\n";
        assert_eq!(fp(CASE).changes_since(&fp(other)), Vec::<String>::new());
    }

    #[test]
    fn title_end_and_budget_may_change() {
        let other = CASE
            .replace("title = \"a\"", "title = \"b\"")
            .replace("end = 1.0", "end = 2.0\nmax_steps = 5");
        assert!(fp(&other).changes_since(&fp(CASE)).is_empty());
    }

    #[test]
    fn a_changed_field_is_named_by_its_path() {
        let other = CASE.replace("mu_s = 0.5", "mu_s = 0.4");
        assert_eq!(
            fp(&other).changes_since(&fp(CASE)),
            vec!["case field interfaces[1].mu_s changed".to_string()]
        );
        let added = CASE.replace("dt = 1e-4", "dt = 1e-4\nsafety = 0.5");
        assert_eq!(
            fp(&added).changes_since(&fp(CASE)),
            vec!["case field time.safety added".to_string()]
        );
        assert_eq!(
            fp(CASE).changes_since(&fp(&added)),
            vec!["case field time.safety removed".to_string()]
        );
    }

    #[test]
    fn a_moved_node_changes_the_mesh_hash() {
        let mut m = Mesh {
            coords: vec![[0.0; 3]; 8],
            elements: vec![[0, 1, 2, 3, 4, 5, 6, 7]],
            ..Mesh::default()
        };
        let before = mesh_hash(&m);
        m.coords[3][1] = 1e-12;
        assert_ne!(before, mesh_hash(&m));
    }

    #[test]
    fn bytes_round_trip() {
        let f = fp(CASE);
        let mut b = f.to_bytes();
        b.extend([1, 2, 3]);
        let (g, used) = CaseFingerprint::from_bytes(&b).unwrap();
        assert_eq!(f, g);
        assert_eq!(used, b.len() - 3);
        assert!(CaseFingerprint::from_bytes(&b[..used - 1]).is_none());
    }
}
