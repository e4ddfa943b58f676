//! Compressed ParaView frames: VTK XML UnstructuredGrid (`.vtu`) of hex8 cells, every array
//! zlib-compressed in VTK's raw appended format — for the many frames of a long run (a
//! 60 s earthquake written every 0.1 s), where [`super::write_vtu`]'s Float64 base64
//! frames of the whole mesh would take tens of gigabytes. The compact frames keep their
//! fields in Float32; the whole-mesh frames of such a run in Float64 (the solver's numbers
//! exactly, at ≈ 0.3 of the base64 file: [`Precision`]).
//!
//! Layout (the one VTK's own `vtkXMLWriter` uses with `vtkZLibDataCompressor` and
//! `SetDataModeToAppended` + `EncodeAppendedDataOff`): after `<AppendedData
//! encoding="raw">_`, each array is a header of UInt64 values — number of blocks, the
//! uncompressed block size, the uncompressed size of the last block (0 when it is a full
//! block), then the compressed size of every block — followed by the blocks, each a zlib
//! stream. A DataArray's `offset` is the byte offset of its header from the `_`.
//!
//! Float32 keeps 7 significant digits: enough for plots and maps, not for restarts (the
//! checkpoints keep the solver's state exactly). Coordinates stay Float64 (model
//! coordinates of 10² m in Float32 would lose the sub-millimetre displacements' geometry).
//! Generic XML parsers cannot read raw appended data; VTK, ParaView and PyVista do.

use std::io::{self, Write};
use std::path::Path;

use flate2::write::ZlibEncoder;
use flate2::Compression;

use super::field_data::VtuStrings;
use super::vtu::{
    cells_attrs, field_attrs, write_head, write_tail, Appended, ArrayTag, VtuField, POINTS_ATTRS,
    VTK_HEXAHEDRON,
};
use super::{atomic::write_atomic_with, label};
use dcfm::error::{DcfmError, Result};

/// Uncompressed size of a block (VTK's default is 32 KiB; larger blocks compress better
/// and the reader decompresses block by block either way).
const BLOCK: usize = 1 << 20;

/// One compressed array: its header and blocks, ready to be appended.
struct Compressed {
    header: Vec<u64>,
    blocks: Vec<Vec<u8>>,
}

impl Compressed {
    fn new(bytes: &[u8], level: Compression) -> io::Result<Self> {
        let mut blocks = Vec::new();
        for chunk in bytes.chunks(BLOCK) {
            let mut e = ZlibEncoder::new(Vec::with_capacity(chunk.len() / 2), level);
            e.write_all(chunk)?;
            blocks.push(e.finish()?);
        }
        let last = bytes.len() % BLOCK;
        let mut header = vec![blocks.len() as u64, BLOCK as u64, last as u64];
        header.extend(blocks.iter().map(|b| b.len() as u64));
        Ok(Self { header, blocks })
    }

    fn len(&self) -> u64 {
        8 * self.header.len() as u64 + self.blocks.iter().map(|b| b.len() as u64).sum::<u64>()
    }

    fn write(&self, w: &mut impl Write) -> io::Result<()> {
        for h in &self.header {
            w.write_all(&h.to_le_bytes())?;
        }
        for b in &self.blocks {
            w.write_all(b)?;
        }
        Ok(())
    }
}

/// The floating-point type the fields are written in (coordinates are always Float64).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Precision {
    /// 7 significant digits: plots and maps of the many compact frames.
    Float32,
    /// The solver's values exactly (the whole-mesh frames).
    Float64,
}

impl Precision {
    fn vtk_type(self) -> &'static str {
        match self {
            Self::Float32 => "Float32",
            Self::Float64 => "Float64",
        }
    }

    fn bytes(self, values: &[f64]) -> Vec<u8> {
        match self {
            Self::Float32 => values
                .iter()
                .flat_map(|&v| (v as f32).to_le_bytes())
                .collect(),
            Self::Float64 => values.iter().flat_map(|&v| v.to_le_bytes()).collect(),
        }
    }
}

/// Write a compressed `.vtu` of hex8 `cells` over `coords` with `point_fields` and
/// `cell_fields` (one tuple per point / cell, as [`super::write_vtu`]) in `precision`,
/// atomically. Errors name the file and the offending field or cell; nothing is written
/// then.
pub fn write_vtu_compressed(
    path: &Path,
    precision: Precision,
    coords: &[[f64; 3]],
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    field_data: &[VtuStrings],
) -> Result<()> {
    super::vtu::check_strings(path, field_data)?;
    super::vtu::check_field_sizes(path, point_fields, coords.len(), cell_fields, cells.len())?;
    if let Some((c, bad)) = cells.iter().enumerate().find_map(|(c, conn)| {
        conn.iter()
            .find(|&&a| a as usize >= coords.len())
            .map(|&a| (c, a))
    }) {
        return Err(DcfmError::invalid(
            label(path),
            format!("cell {c}"),
            format!("node {bad}"),
            format!("node indices below {}", coords.len()),
        ));
    }
    if cells.len() * 8 > i32::MAX as usize {
        return Err(DcfmError::invalid(
            label(path),
            "cells",
            cells.len(),
            "fewer than 2^28 cells (Int32 connectivity)",
        ));
    }
    write_atomic_with(path, |w| {
        write_body(
            w,
            precision,
            coords,
            cells,
            point_fields,
            cell_fields,
            field_data,
        )
    })
}

fn write_body<W: Write>(
    w: &mut W,
    precision: Precision,
    coords: &[[f64; 3]],
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    field_data: &[VtuStrings],
) -> io::Result<()> {
    let level = Compression::fast();
    let mut arrays: Vec<(String, Compressed)> = Vec::new();
    let mut add = |xml: String, bytes: Vec<u8>| -> io::Result<()> {
        arrays.push((xml, Compressed::new(&bytes, level)?));
        Ok(())
    };
    for f in point_fields.iter().chain(cell_fields) {
        add(
            field_attrs(f, precision.vtk_type()),
            precision.bytes(f.values),
        )?;
    }
    let [conn, offsets, types] = cells_attrs("Int32");
    add(
        POINTS_ATTRS.to_string(),
        coords
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect(),
    )?;
    add(
        conn,
        cells
            .iter()
            .flatten()
            .flat_map(|&a| (a as i32).to_le_bytes())
            .collect(),
    )?;
    add(
        offsets,
        (1..=cells.len())
            .flat_map(|c| ((8 * c) as i32).to_le_bytes())
            .collect(),
    )?;
    add(types, vec![VTK_HEXAHEDRON; cells.len()])?;
    let mut tags: Vec<ArrayTag> = Vec::with_capacity(arrays.len());
    let mut next = 0u64;
    for (attrs, a) in &arrays {
        tags.push((attrs.clone(), next));
        next += a.len();
    }
    write_head(
        w,
        Appended::RawZlib,
        field_data,
        coords.len(),
        cells.len(),
        point_fields.len(),
        &tags,
    )?;
    for (_, a) in &arrays {
        a.write(w)?;
    }
    write_tail(w)
}

/// The cells `selected` (element ids, ascending) of a mesh with their own compact node
/// numbering, to write a part of a mesh: local coordinates and connectivity, and the
/// global node of every local one (to gather point fields).
pub struct CellSubset {
    pub coords: Vec<[f64; 3]>,
    pub cells: Vec<[u32; 8]>,
    pub nodes: Vec<u32>,
    pub elements: Vec<u32>,
}

impl CellSubset {
    pub fn new(coords: &[[f64; 3]], elements: &[[u32; 8]], selected: &[u32]) -> Self {
        let mut local = vec![u32::MAX; coords.len()];
        let mut nodes = Vec::new();
        let cells = selected
            .iter()
            .map(|&e| {
                elements[e as usize].map(|n| {
                    if local[n as usize] == u32::MAX {
                        local[n as usize] = nodes.len() as u32;
                        nodes.push(n);
                    }
                    local[n as usize]
                })
            })
            .collect();
        Self {
            coords: nodes.iter().map(|&n| coords[n as usize]).collect(),
            cells,
            nodes,
            elements: selected.to_vec(),
        }
    }

    /// A point field of the whole mesh (`components` per node) restricted to the subset.
    pub fn gather_points(&self, values: &[f64], components: usize) -> Vec<f64> {
        self.nodes
            .iter()
            .flat_map(|&n| {
                let n = n as usize;
                values[components * n..components * (n + 1)].iter().copied()
            })
            .collect()
    }

    /// A cell field of the whole mesh (`components` per element) restricted to the subset.
    pub fn gather_cells(&self, values: &[f64], components: usize) -> Vec<f64> {
        self.elements
            .iter()
            .flat_map(|&e| {
                let e = e as usize;
                values[components * e..components * (e + 1)].iter().copied()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use flate2::read::ZlibDecoder;
    use std::io::Read;

    /// Decode array `k` of a written file from its appended block (the layout the module
    /// doc states), as a reader would.
    fn decode(file: &[u8], offset: usize) -> Vec<u8> {
        let marker = b"encoding=\"raw\">\n   _";
        let start = file
            .windows(marker.len())
            .position(|w| w == marker)
            .unwrap();
        let data = &file[start + marker.len()..];
        let at = |i: usize| {
            u64::from_le_bytes(data[offset + 8 * i..offset + 8 * i + 8].try_into().unwrap())
        };
        let n = at(0) as usize;
        let mut pos = offset + 8 * (3 + n);
        let mut out = Vec::new();
        for b in 0..n {
            let len = at(3 + b) as usize;
            ZlibDecoder::new(&data[pos..pos + len])
                .read_to_end(&mut out)
                .unwrap();
            pos += len;
        }
        out
    }

    /// The `offset` attribute of the DataArray named `name` in a file's text.
    fn array_offset(text: &str, name: &str) -> usize {
        let i = text.find(&format!("Name=\"{name}\"")).unwrap();
        let rest = &text[i..];
        let o = rest.find("offset=\"").unwrap() + 8;
        rest[o..o + rest[o..].find('"').unwrap()]
            .parse::<usize>()
            .unwrap()
    }

    #[test]
    fn arrays_decode_to_the_values_written() {
        let dir = crate::output::test_dir("vtu-compressed");
        let coords: Vec<[f64; 3]> = (0..12)
            .map(|i| [(i % 2) as f64, ((i / 2) % 2) as f64, (i / 4) as f64])
            .collect();
        let cells = vec![[0, 1, 3, 2, 4, 5, 7, 6], [4, 5, 7, 6, 8, 9, 11, 10]];
        let u: Vec<f64> = (0..36).map(|i| 0.25 * i as f64).collect();
        let d = vec![0.5, 1.0];
        let names = vec!["concrete".to_string(), "rock".to_string()];
        let path = dir.join("a.vtu");
        write_vtu_compressed(
            &path,
            Precision::Float32,
            &coords,
            &cells,
            &[VtuField::new("u", 3, &u)],
            &[VtuField::new("damage", 1, &d)],
            &[VtuStrings {
                name: "region_names",
                values: &names,
            }],
        )
        .unwrap();
        let file = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&file);
        // The field data sits in the XML header, before the binary appended block.
        let header = &text[..text.find("<AppendedData").unwrap()];
        assert_eq!(
            crate::output::read_string_arrays(header).unwrap(),
            vec![("region_names".to_string(), names.clone())]
        );
        let offset = |name: &str| array_offset(&text, name);
        let f32s = |b: Vec<u8>| -> Vec<f32> {
            b.chunks(4)
                .map(|c| f32::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        assert_eq!(
            f32s(decode(&file, offset("u"))),
            u.iter().map(|&v| v as f32).collect::<Vec<_>>()
        );
        assert_eq!(f32s(decode(&file, offset("damage"))), vec![0.5, 1.0]);
        let conn: Vec<i32> = decode(&file, offset("connectivity"))
            .chunks(4)
            .map(|c| i32::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(conn[8..], [4, 5, 7, 6, 8, 9, 11, 10]);
        let pts: Vec<f64> = decode(&file, offset("Points"))
            .chunks(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect();
        assert_eq!(pts[33..36], [1.0, 1.0, 2.0]);
        // A wrong field length is an error naming the field; nothing is written.
        let bad = dir.join("b.vtu");
        let e = write_vtu_compressed(
            &bad,
            Precision::Float32,
            &coords,
            &cells,
            &[],
            &[VtuField::new("damage", 1, &u)],
            &[],
        )
        .unwrap_err();
        assert!(e.to_string().contains("'damage'"), "{e}");
        assert!(!bad.exists());
    }

    /// Float64 frames keep the solver's values bit for bit (values Float32 would round),
    /// and the arrays say so in their type; a multi-block array (more than [`BLOCK`] bytes)
    /// decodes whole.
    #[test]
    fn float64_arrays_decode_bit_for_bit() {
        let dir = crate::output::test_dir("vtu-compressed-f64");
        let n_cells = BLOCK / 8 / 6 + 7; // stress: more than one block of Float64
        let coords: Vec<[f64; 3]> = (0..4 * (n_cells + 1))
            .map(|i| [(i % 2) as f64, ((i / 2) % 2) as f64, (i / 4) as f64])
            .collect();
        let cells: Vec<[u32; 8]> = (0..n_cells as u32)
            .map(|c| {
                let b = 4 * c;
                [b, b + 1, b + 3, b + 2, b + 4, b + 5, b + 7, b + 6]
            })
            .collect();
        let u: Vec<f64> = (0..3 * coords.len())
            .map(|i| 1.0 / 3.0 + 1e-12 * i as f64)
            .collect();
        let stress: Vec<f64> = (0..6 * n_cells).map(|i| (i as f64).sqrt() * 1e6).collect();
        let path = dir.join("f64.vtu");
        write_vtu_compressed(
            &path,
            Precision::Float64,
            &coords,
            &cells,
            &[VtuField::new("displacement", 3, &u)],
            &[VtuField::new("stress", 6, &stress)],
            &[],
        )
        .unwrap();
        let file = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&file);
        let header = &text[..text.find("<AppendedData").unwrap()];
        assert!(
            header.contains("type=\"Float64\" Name=\"displacement\""),
            "{header}"
        );
        assert!(
            header.contains("type=\"Float64\" Name=\"stress\""),
            "{header}"
        );
        let offset = |name: &str| array_offset(&text, name);
        let f64s = |b: Vec<u8>| -> Vec<u64> {
            b.chunks(8)
                .map(|c| u64::from_le_bytes(c.try_into().unwrap()))
                .collect()
        };
        let bits = |v: &[f64]| -> Vec<u64> { v.iter().map(|x| x.to_bits()).collect() };
        assert_eq!(f64s(decode(&file, offset("displacement"))), bits(&u));
        assert_eq!(f64s(decode(&file, offset("stress"))), bits(&stress));
    }

    #[test]
    fn subset_renumbers_nodes_and_gathers_fields() {
        let coords: Vec<[f64; 3]> = (0..12).map(|i| [i as f64, 0.0, 0.0]).collect();
        let elements = vec![[0, 1, 3, 2, 4, 5, 7, 6], [4, 5, 7, 6, 8, 9, 11, 10]];
        let s = CellSubset::new(&coords, &elements, &[1]);
        assert_eq!(s.nodes, vec![4, 5, 7, 6, 8, 9, 11, 10]);
        assert_eq!(s.cells, vec![[0, 1, 2, 3, 4, 5, 6, 7]]);
        assert_eq!(s.coords[2], [7.0, 0.0, 0.0]);
        let v: Vec<f64> = (0..12).map(|i| i as f64).collect();
        assert_eq!(s.gather_points(&v, 1)[..3], [4.0, 5.0, 7.0]);
        assert_eq!(s.gather_cells(&[1.0, 2.0, 10.0, 20.0], 2), vec![10.0, 20.0]);
    }
}
