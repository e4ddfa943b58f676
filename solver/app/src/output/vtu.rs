//! ParaView meshes: VTK XML UnstructuredGrid (`.vtu`) of hex8 cells with point and cell
//! fields.
//!
//! The XML header is small and written by hand; every array goes to one `AppendedData`
//! block as base64 of its little-endian binary (`encoding="base64"`,
//! `header_type="UInt64"`: per array, an 8-byte byte count then the values, encoded as one
//! base64 stream, which is how VTK itself writes uncompressed appended data). The values
//! are streamed from the solver's arrays into the (atomic) file with no intermediate copy
//! of the mesh (a VTK crate model would first copy coordinates, connectivity and every
//! field into its own buffers) and no float formatting (ASCII would be ~3× larger and
//! slow to write). Base64 rather than `encoding="raw"`: raw bytes inside XML are read by
//! VTK/ParaView but not by generic XML parsers (vtkio, which our tests use to read the
//! files back, stops at the first `<` byte); base64 costs a third more bytes. Floats are
//! Float64 so post-processing sees the solver's values exactly; connectivity and offsets
//! are Int32 whenever they fit (always, below 2³¹ nodes), halving their size.

use std::io::{self, Write};
use std::path::Path;

use super::field_data::{bad_string, write_field_data, VtuStrings};
use super::{atomic::write_atomic_with, label};
use dcfm::error::{DcfmError, Result};

/// VTK cell type of the 8-node hexahedron.
pub const VTK_HEXAHEDRON: u8 = 12;

/// One named field: `values` holds `components` numbers per point (or per cell), point-major
/// (`[u0x, u0y, u0z, u1x, ...]`).
#[derive(Clone, Copy, Debug)]
pub struct VtuField<'a> {
    pub name: &'a str,
    pub components: usize,
    pub values: &'a [f64],
}

impl<'a> VtuField<'a> {
    /// Field `name` of `components` numbers per point or cell.
    pub fn new(name: &'a str, components: usize, values: &'a [f64]) -> Self {
        Self {
            name,
            components,
            values,
        }
    }
}

/// Integer width of the connectivity and offsets arrays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum IndexType {
    Int32,
    Int64,
}

impl IndexType {
    /// The VTK type name.
    fn name(self) -> &'static str {
        match self {
            IndexType::Int32 => "Int32",
            IndexType::Int64 => "Int64",
        }
    }

    /// Bytes per index.
    fn bytes(self) -> u64 {
        match self {
            IndexType::Int32 => 4,
            IndexType::Int64 => 8,
        }
    }
}

/// Write a `.vtu` file of hex8 `cells` (VTK/Gmsh node order) over `coords`, with
/// `point_fields` (one tuple per point), `cell_fields` (one tuple per cell) and the
/// string arrays `field_data` of the whole data set (`output::field_data`), atomically.
///
/// Errors name the file and the offending field (wrong length, zero components, a NUL
/// byte in a string) or cell (node index out of range); nothing is written then.
pub fn write_vtu(
    path: &Path,
    coords: &[[f64; 3]],
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    field_data: &[VtuStrings],
) -> Result<()> {
    let fits_i32 =
        coords.len() <= i32::MAX as usize && cells.len().saturating_mul(8) <= i32::MAX as usize;
    let index = if fits_i32 {
        IndexType::Int32
    } else {
        IndexType::Int64
    };
    write_vtu_with(
        path,
        coords,
        cells,
        point_fields,
        cell_fields,
        field_data,
        index,
    )
}

fn write_vtu_with(
    path: &Path,
    coords: &[[f64; 3]],
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    field_data: &[VtuStrings],
    index: IndexType,
) -> Result<()> {
    check(path, coords.len(), cells, point_fields, cell_fields)?;
    check_strings(path, field_data)?;
    write_atomic_with(path, |w| {
        write_body(
            w,
            coords,
            cells,
            point_fields,
            cell_fields,
            field_data,
            index,
        )
    })
}

/// Refuse a string that the format cannot hold (a NUL byte ends a string there).
pub(crate) fn check_strings(path: &Path, field_data: &[VtuStrings]) -> Result<()> {
    match bad_string(field_data) {
        Some((name, k, value)) => Err(DcfmError::invalid(
            label(path),
            format!("field data '{name}'[{k}]"),
            format!("{value:?}"),
            "a string without NUL bytes",
        )),
        None => Ok(()),
    }
}

/// Refuse fields of the wrong size ([`check_field_sizes`]) and cells with a node index
/// beyond the `n_points` points, naming `path` and the field or cell.
fn check(
    path: &Path,
    n_points: usize,
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
) -> Result<()> {
    check_field_sizes(path, point_fields, n_points, cell_fields, cells.len())?;
    for (c, conn) in cells.iter().enumerate() {
        if let Some(bad) = conn.iter().find(|&&a| a as usize >= n_points) {
            return Err(DcfmError::invalid(
                label(path),
                format!("cell {c}"),
                format!("node {bad}"),
                format!("node indices below {n_points}"),
            ));
        }
    }
    Ok(())
}

/// Refuse a field without components or without `components` values for each of the
/// `n_points` points (`point_fields`) or `n_cells` cells (`cell_fields`), naming `path`
/// and the field ([`write_vtu`], [`write_vtu_lines`], `super::vtu_compressed`).
pub(crate) fn check_field_sizes(
    path: &Path,
    point_fields: &[VtuField],
    n_points: usize,
    cell_fields: &[VtuField],
    n_cells: usize,
) -> Result<()> {
    for (kind, fields, n) in [
        ("point", point_fields, n_points),
        ("cell", cell_fields, n_cells),
    ] {
        for f in fields {
            if f.components == 0 || f.values.len() != f.components * n {
                return Err(DcfmError::invalid(
                    label(path),
                    format!("{kind} field '{}'", f.name),
                    format!("{} values, {} components", f.values.len(), f.components),
                    format!("components >= 1 and components x {n} values ({n} {kind}s)"),
                ));
            }
        }
    }
    Ok(())
}

/// Escape a string for an XML attribute value.
pub(crate) fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for ch in s.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// How a `.vtu`'s arrays are appended after its XML head.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Appended {
    /// Base64 text ([`write_vtu`], [`write_vtu_lines`]).
    Base64,
    /// Raw bytes, every array zlib-compressed (`super::vtu_compressed`).
    RawZlib,
}

/// One DataArray of a `.vtu`'s XML head: the attributes that say what it holds (`type`,
/// `Name`, `NumberOfComponents`) and its offset in the appended data.
pub(crate) type ArrayTag = (String, u64);

/// The attributes of field `f` stored as `value_type` (`Float64`, `Float32`).
pub(crate) fn field_attrs(f: &VtuField, value_type: &str) -> String {
    format!(
        "type=\"{value_type}\" Name=\"{}\" NumberOfComponents=\"{}\"",
        xml_escape(f.name),
        f.components
    )
}

/// The attributes of the points' DataArray (Float64 coordinates).
pub(crate) const POINTS_ATTRS: &str = "type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\"";

/// The attributes of the cells' connectivity, offsets and types DataArrays, the indices
/// stored as `index_type` (`Int32`, `Int64`).
pub(crate) fn cells_attrs(index_type: &str) -> [String; 3] {
    [
        format!("type=\"{index_type}\" Name=\"connectivity\""),
        format!("type=\"{index_type}\" Name=\"offsets\""),
        "type=\"UInt8\" Name=\"types\"".to_string(),
    ]
}

/// The XML of a one-piece UnstructuredGrid up to the `_` that opens its appended data, as
/// VTK's `vtkXMLWriter` writes it in appended mode: the `VTKFile` element (naming VTK's
/// zlib compressor for [`Appended::RawZlib`]), the data set's `field_data`, a piece of
/// `n_points` points and `n_cells` cells, and a DataArray for each of `arrays` — the
/// `n_point_fields` point fields, then the cell fields, the points, and the cells'
/// connectivity, offsets and types (always the last four).
pub(crate) fn write_head<W: Write>(
    w: &mut W,
    appended: Appended,
    field_data: &[VtuStrings],
    n_points: usize,
    n_cells: usize,
    n_point_fields: usize,
    arrays: &[ArrayTag],
) -> io::Result<()> {
    let (compressor, encoding) = match appended {
        Appended::Base64 => ("", "base64"),
        Appended::RawZlib => (" compressor=\"vtkZLibDataCompressor\"", "raw"),
    };
    writeln!(w, "<?xml version=\"1.0\"?>")?;
    writeln!(
        w,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\"{compressor}>"
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    write_field_data(w, field_data, 4)?;
    writeln!(
        w,
        "    <Piece NumberOfPoints=\"{n_points}\" NumberOfCells=\"{n_cells}\">"
    )?;
    let (point_fields, rest) = arrays.split_at(n_point_fields);
    let (cell_fields, rest) = rest.split_at(rest.len() - 4);
    let (points, cells) = rest.split_at(1);
    for (section, tags) in [
        ("PointData", point_fields),
        ("CellData", cell_fields),
        ("Points", points),
        ("Cells", cells),
    ] {
        writeln!(w, "      <{section}>")?;
        for (attrs, offset) in tags {
            writeln!(
                w,
                "        <DataArray {attrs} format=\"appended\" offset=\"{offset}\"/>"
            )?;
        }
        writeln!(w, "      </{section}>")?;
    }
    writeln!(w, "    </Piece>")?;
    writeln!(w, "  </UnstructuredGrid>")?;
    write!(w, "  <AppendedData encoding=\"{encoding}\">\n   _")
}

/// What closes a `.vtu` after its appended data.
pub(crate) fn write_tail(w: &mut impl Write) -> io::Result<()> {
    write!(w, "\n  </AppendedData>\n</VTKFile>\n")
}

/// The DataArrays of a base64 appended block, each at its offset in base64 characters
/// (every array is an 8-byte length header + data, encoded and padded on its own), and
/// the length of the block so far.
struct Base64Tags {
    tags: Vec<ArrayTag>,
    end: u64,
}

impl Base64Tags {
    /// The arrays [`put_fields_and_points`] appends: the point fields, the cell fields
    /// (Float64) and the points.
    fn fields_and_points(
        point_fields: &[VtuField],
        cell_fields: &[VtuField],
        n_points: usize,
    ) -> Self {
        let mut t = Self {
            tags: Vec::with_capacity(point_fields.len() + cell_fields.len() + 4),
            end: 0,
        };
        for f in point_fields.iter().chain(cell_fields) {
            t.push(field_attrs(f, "Float64"), 8 * f.values.len() as u64);
        }
        t.push(POINTS_ATTRS.to_string(), 24 * n_points as u64);
        t
    }

    /// Append an array of `attrs` holding `bytes` bytes.
    fn push(&mut self, attrs: String, bytes: u64) {
        self.tags.push((attrs, self.end));
        self.end += 4 * (8 + bytes).div_ceil(3);
    }

    /// Append the arrays [`put_cells`] appends for `n_cells` cells of `per_cell` nodes.
    fn cells(&mut self, n_cells: u64, per_cell: u64, index: IndexType) {
        let [conn, offsets, types] = cells_attrs(index.name());
        self.push(conn, per_cell * n_cells * index.bytes());
        self.push(offsets, n_cells * index.bytes());
        self.push(types, n_cells);
    }
}

fn write_body<W: Write>(
    w: &mut W,
    coords: &[[f64; 3]],
    cells: &[[u32; 8]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    field_data: &[VtuStrings],
    index: IndexType,
) -> io::Result<()> {
    let mut layout = Base64Tags::fields_and_points(point_fields, cell_fields, coords.len());
    layout.cells(cells.len() as u64, 8, index);
    write_head(
        w,
        Appended::Base64,
        field_data,
        coords.len(),
        cells.len(),
        point_fields.len(),
        &layout.tags,
    )?;
    let mut b = Base64Writer::new(w);
    put_fields_and_points(&mut b, point_fields, cell_fields, coords)?;
    put_cells(&mut b, cells.as_flattened(), 8, VTK_HEXAHEDRON, index)?;
    debug_assert_eq!(b.written, layout.end);
    b.flush()?;
    write_tail(w)
}

const B64: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// The appended arrays every writer starts with, in header order: the point fields, the
/// cell fields, then the points (each array: its byte count, then little-endian Float64).
fn put_fields_and_points<W: Write>(
    b: &mut Base64Writer<'_, W>,
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
    points: &[[f64; 3]],
) -> io::Result<()> {
    for f in point_fields.iter().chain(cell_fields) {
        b.put(&(8 * f.values.len() as u64).to_le_bytes())?;
        for v in f.values {
            b.put(&v.to_le_bytes())?;
        }
        b.end_array()?;
    }
    b.put(&(24 * points.len() as u64).to_le_bytes())?;
    for p in points {
        for v in p {
            b.put(&v.to_le_bytes())?;
        }
    }
    b.end_array()
}

/// The cells' arrays every writer ends with: the connectivity `conn` (`per_cell` node
/// indices a cell), the offsets and the types (all `cell_type`), each array its byte count
/// then its values, the indices as `index`.
fn put_cells<W: Write>(
    b: &mut Base64Writer<'_, W>,
    conn: &[u32],
    per_cell: u64,
    cell_type: u8,
    index: IndexType,
) -> io::Result<()> {
    let put_index = |b: &mut Base64Writer<'_, W>, v: u64| match index {
        IndexType::Int32 => b.put(&(v as i32).to_le_bytes()),
        IndexType::Int64 => b.put(&(v as i64).to_le_bytes()),
    };
    let n_cells = conn.len() as u64 / per_cell;
    b.put(&(conn.len() as u64 * index.bytes()).to_le_bytes())?;
    for &a in conn {
        put_index(b, a as u64)?;
    }
    b.end_array()?;
    b.put(&(n_cells * index.bytes()).to_le_bytes())?;
    for i in 1..=n_cells {
        put_index(b, per_cell * i)?;
    }
    b.end_array()?;
    b.put(&n_cells.to_le_bytes())?;
    for _ in 0..n_cells {
        b.put(&[cell_type])?;
    }
    b.end_array()
}

/// Streaming base64 encoder: bytes in, characters out in 64 KiB chunks; `end_array` pads
/// the current array so the next one starts on its own 4-character group.
struct Base64Writer<'w, W: Write> {
    w: &'w mut W,
    pending: [u8; 3],
    n_pending: usize,
    out: Vec<u8>,
    /// Characters produced so far (checked against the offsets in the header).
    written: u64,
}

impl<'w, W: Write> Base64Writer<'w, W> {
    fn new(w: &'w mut W) -> Self {
        Self {
            w,
            pending: [0; 3],
            n_pending: 0,
            out: Vec::with_capacity(1 << 16),
            written: 0,
        }
    }

    #[inline]
    fn put(&mut self, bytes: &[u8]) -> io::Result<()> {
        for &byte in bytes {
            self.pending[self.n_pending] = byte;
            self.n_pending += 1;
            if self.n_pending == 3 {
                self.emit(3);
                if self.out.len() >= (1 << 16) - 4 {
                    self.flush()?;
                }
            }
        }
        Ok(())
    }

    /// Encode the pending group (`n` = 1..=3 real bytes) as four characters.
    #[inline]
    fn emit(&mut self, n: usize) {
        let [a, b, c] = self.pending;
        let (b, c) = (if n > 1 { b } else { 0 }, if n > 2 { c } else { 0 });
        let chars = [
            B64[(a >> 2) as usize],
            B64[(((a & 0x03) << 4) | (b >> 4)) as usize],
            if n > 1 {
                B64[(((b & 0x0f) << 2) | (c >> 6)) as usize]
            } else {
                b'='
            },
            if n > 2 {
                B64[(c & 0x3f) as usize]
            } else {
                b'='
            },
        ];
        self.out.extend_from_slice(&chars);
        self.written += 4;
        self.n_pending = 0;
    }

    fn end_array(&mut self) -> io::Result<()> {
        if self.n_pending > 0 {
            self.emit(self.n_pending);
        }
        Ok(())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.w.write_all(&self.out)?;
        self.out.clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_dir;
    use vtkio::model::{Attribute, CellType, DataSet, Piece, VertexNumbers};

    /// A 2×1×1 block of hex8 cells with awkward coordinates.
    fn two_cells() -> (Vec<[f64; 3]>, Vec<[u32; 8]>) {
        let mut coords = Vec::new();
        for k in 0..2 {
            for j in 0..2 {
                for i in 0..3 {
                    coords.push([
                        i as f64 * 0.1 + 1e-3 * j as f64,
                        j as f64 * std::f64::consts::PI,
                        k as f64 * 1.0e-7 - 3.3,
                    ]);
                }
            }
        }
        let id = |i: u32, j: u32, k: u32| i + 3 * j + 6 * k;
        let cells = (0..2)
            .map(|i| {
                [
                    id(i, 0, 0),
                    id(i + 1, 0, 0),
                    id(i + 1, 1, 0),
                    id(i, 1, 0),
                    id(i, 0, 1),
                    id(i + 1, 0, 1),
                    id(i + 1, 1, 1),
                    id(i, 1, 1),
                ]
            })
            .collect();
        (coords, cells)
    }

    fn read_back(path: &Path) -> vtkio::model::UnstructuredGridPiece {
        let vtk = vtkio::Vtk::import(path).expect("vtkio reads the file");
        match vtk.data {
            DataSet::UnstructuredGrid { mut pieces, .. } => match pieces.remove(0) {
                Piece::Inline(p) => *p,
                other => panic!("unexpected piece {other:?}"),
            },
            other => panic!("unexpected data set {other:?}"),
        }
    }

    fn field_values(attrs: &[Attribute], name: &str) -> (usize, Vec<f64>) {
        for a in attrs {
            if let Attribute::DataArray(d) = a {
                if d.name == name {
                    let n = match d.elem {
                        vtkio::model::ElementType::Vectors => 3,
                        vtkio::model::ElementType::Scalars { num_comp, .. } => num_comp as usize,
                        vtkio::model::ElementType::Generic(n) => n as usize,
                        ref other => panic!("unexpected element type {other:?}"),
                    };
                    return (n, d.data.clone().cast_into::<f64>().unwrap());
                }
            }
        }
        panic!("no field {name}");
    }

    fn round_trip(index: IndexType) {
        let dir = test_dir("vtu");
        let path = dir.join("mesh_000001.vtu");
        let (coords, cells) = two_cells();
        let u: Vec<f64> = (0..coords.len() * 3)
            .map(|i| (i as f64).sin() * 1e-3)
            .collect();
        let p: Vec<f64> = (0..coords.len()).map(|i| -(i as f64) * 1.5e6).collect();
        let damage = [0.25, 1.0];
        let stress: Vec<f64> = (0..12).map(|i| i as f64 * 1e5 + 0.125).collect();
        let names = vec!["rock".to_string(), "dam <body> & \"core\"".to_string()];
        write_vtu_with(
            &path,
            &coords,
            &cells,
            &[
                VtuField::new("displacement", 3, &u),
                VtuField::new("pore<&>", 1, &p),
            ],
            &[
                VtuField::new("damage", 1, &damage),
                VtuField::new("stress", 6, &stress),
            ],
            &[VtuStrings {
                name: "region_names",
                values: &names,
            }],
            index,
        )
        .unwrap();
        // The field data is readable beside the numeric arrays (vtkio skips it).
        let text = std::fs::read_to_string(&path).unwrap();
        assert_eq!(
            crate::output::read_string_arrays(&text).unwrap(),
            vec![("region_names".to_string(), names)]
        );
        let piece = read_back(&path);
        assert_eq!(piece.num_points(), coords.len());
        let pts: Vec<f64> = piece.points.cast_into::<f64>().unwrap();
        assert_eq!(pts, coords.iter().flatten().copied().collect::<Vec<_>>());
        let (conn, offsets) = match piece.cells.cell_verts {
            VertexNumbers::XML {
                connectivity,
                offsets,
            } => (connectivity, offsets),
            other => panic!("unexpected cells {other:?}"),
        };
        let expect: Vec<u64> = cells.iter().flatten().map(|&a| a as u64).collect();
        assert_eq!(conn, expect);
        assert_eq!(offsets, vec![8, 16]);
        assert_eq!(piece.cells.types, vec![CellType::Hexahedron; 2]);
        assert_eq!(field_values(&piece.data.point, "displacement"), (3, u));
        assert_eq!(field_values(&piece.data.point, "pore<&>"), (1, p));
        assert_eq!(
            field_values(&piece.data.cell, "damage"),
            (1, damage.to_vec())
        );
        assert_eq!(field_values(&piece.data.cell, "stress"), (6, stress));
    }

    #[test]
    fn base64_matches_rfc4648_vectors() {
        for (input, expect) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            let mut out = Vec::new();
            let mut b = Base64Writer::new(&mut out);
            b.put(input.as_bytes()).unwrap();
            b.end_array().unwrap();
            assert_eq!(b.written as usize, expect.len());
            b.flush().unwrap();
            assert_eq!(String::from_utf8(out).unwrap(), expect);
        }
    }

    #[test]
    fn round_trip_int32_indices() {
        round_trip(IndexType::Int32);
    }

    #[test]
    fn round_trip_int64_indices() {
        round_trip(IndexType::Int64);
    }

    #[test]
    fn no_fields_and_no_cells() {
        let dir = test_dir("vtu-empty");
        let path = dir.join("empty.vtu");
        write_vtu(&path, &[[0.0; 3]], &[], &[], &[], &[]).unwrap();
        let piece = read_back(&path);
        assert_eq!(piece.num_points(), 1);
        assert_eq!(piece.cells.types.len(), 0);
    }

    #[test]
    fn bad_field_length_names_file_and_field() {
        let dir = test_dir("vtu-bad");
        let path = dir.join("bad.vtu");
        let (coords, cells) = two_cells();
        let short = [1.0; 5];
        let err = write_vtu(
            &path,
            &coords,
            &cells,
            &[VtuField::new("velocity", 3, &short)],
            &[],
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(err.contains("bad.vtu") && err.contains("velocity"), "{err}");
        assert!(err.contains("5 values, 3 components"), "{err}");
        assert!(err.contains("components x 12 values (12 points)"), "{err}");
        assert!(!path.exists());
        let mut bad_cells = cells.clone();
        bad_cells[1][3] = 99;
        let err = write_vtu(&path, &coords, &bad_cells, &[], &[], &[])
            .unwrap_err()
            .to_string();
        assert!(err.contains("cell 1") && err.contains("99"), "{err}");
        let names = vec!["rock".to_string(), "a\0b".to_string()];
        let err = write_vtu(
            &path,
            &coords,
            &cells,
            &[],
            &[],
            &[VtuStrings {
                name: "region_names",
                values: &names,
            }],
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("bad.vtu") && err.contains("field data 'region_names'[1]"),
            "{err}"
        );
        assert!(!path.exists());
    }
}

/// VTK cell type of the 2-node line.
pub const VTK_LINE: u8 = 3;

/// Write a `.vtu` file of 2-node line cells (anchor-bar segments) over `points`, with one
/// tuple per point in `point_fields` and per line in `cell_fields`, atomically (same
/// encoding as [`write_vtu`]; Int64 indices).
pub fn write_vtu_lines(
    path: &Path,
    points: &[[f64; 3]],
    lines: &[[u32; 2]],
    point_fields: &[VtuField],
    cell_fields: &[VtuField],
) -> Result<()> {
    check_field_sizes(path, point_fields, points.len(), cell_fields, lines.len())?;
    if let Some((c, l)) = lines
        .iter()
        .enumerate()
        .find(|(_, l)| l.iter().any(|&a| a as usize >= points.len()))
    {
        return Err(DcfmError::invalid(
            label(path),
            format!("line {c}"),
            format!("{l:?}"),
            format!("point indices below {}", points.len()),
        ));
    }
    write_atomic_with(path, |w| {
        let mut layout = Base64Tags::fields_and_points(point_fields, cell_fields, points.len());
        layout.cells(lines.len() as u64, 2, IndexType::Int64);
        write_head(
            w,
            Appended::Base64,
            &[],
            points.len(),
            lines.len(),
            point_fields.len(),
            &layout.tags,
        )?;
        let mut b = Base64Writer::new(w);
        put_fields_and_points(&mut b, point_fields, cell_fields, points)?;
        put_cells(&mut b, lines.as_flattened(), 2, VTK_LINE, IndexType::Int64)?;
        debug_assert_eq!(b.written, layout.end);
        b.flush()?;
        write_tail(w)
    })
}

#[cfg(test)]
mod line_tests {
    use super::*;
    use crate::output::test_dir;
    use vtkio::model::{DataSet, Piece, VertexNumbers};

    #[test]
    fn lines_round_trip_through_vtkio() {
        let dir = test_dir("vtu-lines");
        let path = dir.join("anchors.vtu");
        let points = [[0.0, 0.0, 0.0], [0.0, 0.0, 0.5], [0.0, 0.0, 1.25]];
        let lines = [[0, 1], [1, 2]];
        let force = [1.5e5, -2.0e3];
        write_vtu_lines(
            &path,
            &points,
            &lines,
            &[],
            &[VtuField::new("axial_force", 1, &force)],
        )
        .unwrap();
        let vtk = vtkio::Vtk::import(&path).expect("vtkio reads the file");
        let DataSet::UnstructuredGrid { mut pieces, .. } = vtk.data else {
            panic!("not a grid")
        };
        let Piece::Inline(p) = pieces.remove(0) else {
            panic!("not inline")
        };
        assert_eq!(
            p.points.cast_into::<f64>().unwrap(),
            points.iter().flatten().copied().collect::<Vec<_>>()
        );
        match p.cells.cell_verts {
            VertexNumbers::XML {
                connectivity,
                offsets,
            } => {
                assert_eq!(connectivity, vec![0, 1, 1, 2]);
                assert_eq!(offsets, vec![2, 4]);
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(p.cells.types, vec![vtkio::model::CellType::Line; 2]);
        let bad = write_vtu_lines(&path, &points, &[[0, 7]], &[], &[])
            .unwrap_err()
            .to_string();
        assert!(bad.contains("line 0"), "{bad}");
    }
}
