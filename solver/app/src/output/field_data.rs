//! Named string arrays of a VTK XML data set (`<FieldData>`), e.g. `region_names`: the
//! names behind the integer `region` cell field, which ParaView shows in its Information
//! panel and spreadsheet view.
//!
//! VTK writes a `vtkStringArray` as an `<Array type="String">` element (not
//! `<DataArray>`, which is for numeric arrays) with `NumberOfTuples` strings; in ASCII
//! format every string is the decimal codes of its bytes, each string ended by a 0
//! (vtkXMLWriter's ASCII string writer, read back by vtkXMLDataParser; bytes above 127
//! are written here as 128..255, which VTK 9 reads back as the same UTF-8 string, where
//! VTK writes them as negative signed chars). The arrays are
//! few and short, so ASCII is used whatever the encoding of the numeric arrays: an
//! appended string array would need its own byte-count header in the appended block.

use std::io::{self, Write};

use super::vtu::xml_escape;

/// One named array of strings, written as field data of the whole data set.
#[derive(Clone, Copy, Debug)]
pub struct VtuStrings<'a> {
    pub name: &'a str,
    pub values: &'a [String],
}

/// The first string of `arrays` that cannot be written (it holds a NUL byte, the
/// terminator of the format), as (array name, index, string).
pub(crate) fn bad_string(arrays: &[VtuStrings]) -> Option<(String, usize, String)> {
    arrays.iter().find_map(|a| {
        a.values
            .iter()
            .position(|s| s.as_bytes().contains(&0))
            .map(|k| (a.name.to_string(), k, a.values[k].clone()))
    })
}

/// Write `<FieldData>` with `arrays` (nothing when there are none), at `indent` spaces.
pub(crate) fn write_field_data<W: Write>(
    w: &mut W,
    arrays: &[VtuStrings],
    indent: usize,
) -> io::Result<()> {
    if arrays.is_empty() {
        return Ok(());
    }
    let pad = " ".repeat(indent);
    writeln!(w, "{pad}<FieldData>")?;
    for a in arrays {
        writeln!(
            w,
            "{pad}  <Array type=\"String\" Name=\"{}\" NumberOfTuples=\"{}\" format=\"ascii\">",
            xml_escape(a.name),
            a.values.len()
        )?;
        write!(w, "{pad}   ")?;
        for s in a.values {
            for b in s.bytes() {
                write!(w, " {b}")?;
            }
            write!(w, " 0")?;
        }
        writeln!(w)?;
        writeln!(w, "{pad}  </Array>")?;
    }
    writeln!(w, "{pad}</FieldData>")
}

/// The string arrays of the `<FieldData>` of a VTK XML file's text, as (name, strings) —
/// a small reader of the format above for tests and tools (the XML crates the tests use
/// for the numeric arrays skip field data). `None` when an `<Array type="String">` is
/// malformed: its codes are not bytes, its last string is not ended by a 0, or it holds
/// another number of strings than its `NumberOfTuples`.
pub fn read_string_arrays(xml: &str) -> Option<Vec<(String, Vec<String>)>> {
    let mut out = Vec::new();
    let Some(start) = xml.find("<FieldData>") else {
        return Some(out);
    };
    let end = start + xml[start..].find("</FieldData>")?;
    let mut rest = &xml[start..end];
    while let Some(k) = rest.find("<Array ") {
        rest = &rest[k..];
        let close = rest.find('>')?;
        let tag = &rest[..close];
        let attr = |key: &str| -> Option<String> {
            let i = tag.find(&format!(" {key}=\""))? + key.len() + 3;
            let j = tag[i..].find('"')?;
            Some(tag[i..i + j].to_string())
        };
        let body_end = rest.find("</Array>")?;
        let body = &rest[close + 1..body_end];
        if attr("type")? == "String" && attr("format")? == "ascii" {
            let mut strings = Vec::new();
            let mut current = Vec::new();
            for code in body.split_whitespace() {
                // VTK itself writes the bytes as signed chars (-128..127).
                let b = match code.parse::<i16>().ok()? {
                    c @ -128..=-1 => (c + 256) as u8,
                    c @ 0..=255 => c as u8,
                    _ => return None,
                };
                if b == 0 {
                    strings.push(String::from_utf8(std::mem::take(&mut current)).ok()?);
                } else {
                    current.push(b);
                }
            }
            let tuples: usize = attr("NumberOfTuples")?.parse().ok()?;
            if !current.is_empty() || strings.len() != tuples {
                return None;
            }
            let name = attr("Name")?
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&quot;", "\"")
                .replace("&apos;", "'")
                .replace("&amp;", "&");
            out.push((name, strings));
        }
        rest = &rest[body_end..];
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_are_byte_codes_each_ended_by_zero() {
        let names = vec!["rock".to_string(), "dam body".to_string(), String::new()];
        let mut out = Vec::new();
        write_field_data(
            &mut out,
            &[VtuStrings {
                name: "region_names",
                values: &names,
            }],
            4,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        // "rock" = 114 111 99 107, "dam body" = 100 97 109 32 98 111 100 121 (ASCII).
        assert!(
            text.contains(" 114 111 99 107 0 100 97 109 32 98 111 100 121 0 0\n"),
            "{text}"
        );
        assert!(text.contains(
            "<Array type=\"String\" Name=\"region_names\" NumberOfTuples=\"3\" format=\"ascii\">"
        ));
        assert_eq!(
            read_string_arrays(&text).unwrap(),
            vec![("region_names".to_string(), names)]
        );
    }

    #[test]
    fn non_ascii_names_and_escaped_array_names_round_trip() {
        let names = vec!["béton <C30>".to_string(), "岩".to_string()];
        let mut out = Vec::new();
        write_field_data(
            &mut out,
            &[VtuStrings {
                name: "a&b",
                values: &names,
            }],
            0,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        assert!(!text.contains("<C30>"), "{text}");
        assert_eq!(
            read_string_arrays(&text).unwrap(),
            vec![("a&b".to_string(), names)]
        );
    }

    #[test]
    fn malformed_arrays_are_not_read() {
        let unterminated = "<FieldData><Array type=\"String\" Name=\"n\" NumberOfTuples=\"1\" format=\"ascii\"> 97 98 </Array></FieldData>";
        assert_eq!(read_string_arrays(unterminated), None);
        let count = "<FieldData><Array type=\"String\" Name=\"n\" NumberOfTuples=\"2\" format=\"ascii\"> 97 0 </Array></FieldData>";
        assert_eq!(read_string_arrays(count), None);
        assert_eq!(read_string_arrays("<VTKFile/>"), Some(vec![]));
        // VTK's own signed-char form of "é" (0xC3 0xA9).
        let signed = "<FieldData><Array type=\"String\" Name=\"n\" NumberOfTuples=\"1\" format=\"ascii\"> -61 -87 0 </Array></FieldData>";
        assert_eq!(
            read_string_arrays(signed),
            Some(vec![("n".to_string(), vec!["é".to_string()])])
        );
    }

    #[test]
    fn a_nul_byte_is_found() {
        let ok = vec!["a".to_string()];
        let bad = vec!["a".to_string(), "b\0c".to_string()];
        assert_eq!(
            bad_string(&[
                VtuStrings {
                    name: "x",
                    values: &ok
                },
                VtuStrings {
                    name: "y",
                    values: &bad
                }
            ]),
            Some(("y".to_string(), 1, "b\0c".to_string()))
        );
    }
}
