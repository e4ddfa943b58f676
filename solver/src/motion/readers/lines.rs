//! Line-oriented parsing shared by the readers: a cursor over the lines of a file that
//! names the line in every error, number tokens (free-form and Fortran fixed-width), and
//! the reading of exactly `npts` values.
//!
//! Fortran `E`/`F` edit descriptors write numbers in fixed-width fields that can run into
//! each other (`2.3489E-2-1.6646E-2`, the USGS SMC data lines); [`split_free`] splits such
//! runs at a sign that follows a digit or a point, and [`split_fixed`] cuts a line into
//! fields of a given width.

use crate::error::{DcfmError, Result};

/// A cursor over the lines of one file.
pub(crate) struct Lines<'a> {
    label: &'a str,
    lines: Vec<&'a str>,
    pos: usize,
}

impl<'a> Lines<'a> {
    /// The lines of `text`; `label` names the file in errors.
    pub fn new(text: &'a str, label: &'a str) -> Self {
        Self {
            label,
            lines: text.lines().collect(),
            pos: 0,
        }
    }

    /// 1-based number of the next line.
    pub fn line_number(&self) -> usize {
        self.pos + 1
    }

    /// True when every line has been consumed.
    pub fn at_end(&self) -> bool {
        self.pos >= self.lines.len()
    }

    /// Peek at the next line without consuming it.
    pub fn peek(&self) -> Option<&'a str> {
        self.lines.get(self.pos).copied()
    }

    /// The next line and its 1-based number; at the end of the file an error saying what
    /// was expected there.
    pub fn next(&mut self, what: &str) -> Result<(usize, &'a str)> {
        match self.lines.get(self.pos) {
            Some(l) => {
                self.pos += 1;
                Ok((self.pos, l))
            }
            None => Err(self.error(self.pos + 1, "end of file", what)),
        }
    }

    /// An error about line `line`.
    pub fn error(&self, line: usize, value: impl std::fmt::Display, expected: &str) -> DcfmError {
        line_error(self.label, line, value, expected)
    }

    /// Read exactly `npts` numbers from the following lines, each line split by `split`;
    /// stops at the line where `npts` values are complete. `what` names the series.
    pub fn read_values(
        &mut self,
        npts: usize,
        what: &str,
        split: &dyn Fn(&str) -> Vec<String>,
    ) -> Result<Vec<f64>> {
        let mut values = Vec::with_capacity(npts.min(1 << 24));
        while values.len() < npts {
            let Some(line) = self.peek() else {
                return Err(line_error(
                    self.label,
                    self.pos + 1,
                    format!("end of file after {} values", values.len()),
                    &format!("{npts} {what} values (npts in the header)"),
                ));
            };
            let n = self.pos + 1;
            let tokens = split(line);
            if tokens.is_empty() {
                self.pos += 1;
                continue;
            }
            if values.len() + tokens.len() > npts {
                return Err(line_error(
                    self.label,
                    n,
                    format!("{} values so far", values.len() + tokens.len()),
                    &format!("{npts} {what} values (npts in the header disagrees with the data)"),
                ));
            }
            for t in tokens {
                values.push(
                    parse_number(&t)
                        .map_err(|e| line_error(self.label, n, &e, "a finite number"))?,
                );
            }
            self.pos += 1;
        }
        Ok(values)
    }

    /// After the data: the remaining lines must hold no more numbers (else the header's
    /// npts disagrees with the data). Lines for which `stop` is true end the check.
    pub fn expect_no_more_values(
        &mut self,
        npts: usize,
        stop: &dyn Fn(&str) -> bool,
    ) -> Result<()> {
        while let Some(line) = self.peek() {
            if stop(line) {
                return Ok(());
            }
            let n = self.pos + 1;
            if split_free(line).iter().any(|t| parse_number(t).is_ok()) {
                return Err(line_error(
                    self.label,
                    n,
                    format!("more values after the {npts} of the header"),
                    "npts in the header to match the data",
                ));
            }
            self.pos += 1;
        }
        Ok(())
    }
}

/// `file: line N = value: expected`.
pub(crate) fn line_error(
    label: &str,
    line: usize,
    value: impl std::fmt::Display,
    expected: &str,
) -> DcfmError {
    DcfmError::invalid(label, format!("line {line}"), value, expected)
}

/// A finite number from a token: decimal or exponent form, Fortran `D` exponents
/// accepted. `Err` holds the token quoted, for the error message.
pub(crate) fn parse_number(token: &str) -> std::result::Result<f64, String> {
    let t = token.trim();
    // Rust's parser also reads "inf" and "NaN": they come out non-finite and are refused.
    let parsed = t.parse::<f64>().or_else(|_| {
        if t.contains(['D', 'd']) && !t.contains(['i', 'I', 'n', 'N']) {
            t.replace(['D', 'd'], "e").parse::<f64>()
        } else {
            "x".parse::<f64>()
        }
    });
    match parsed {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("\"{t}\" (not a finite number)")),
        Err(_) => Err(format!("\"{t}\"")),
    }
}

/// Tokens of a free-format line: split at white space, commas and semicolons, and inside
/// a token at a sign that follows a digit or a point (Fortran fields that run together).
pub(crate) fn split_free(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    for raw in line.split(|c: char| c.is_whitespace() || c == ',' || c == ';') {
        if raw.is_empty() {
            continue;
        }
        let b = raw.as_bytes();
        let mut start = 0;
        for i in 1..b.len() {
            let prev = b[i - 1];
            if (b[i] == b'-' || b[i] == b'+') && (prev.is_ascii_digit() || prev == b'.') {
                out.push(raw[start..i].to_string());
                start = i;
            }
        }
        out.push(raw[start..].to_string());
    }
    out
}

/// Fields of `width` characters (the last may be shorter; blank fields are skipped).
pub(crate) fn split_fixed(line: &str, width: usize) -> Vec<String> {
    let chars: Vec<char> = line.trim_end().chars().collect();
    chars
        .chunks(width.max(1))
        .map(|c| c.iter().collect::<String>())
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().to_string())
        .collect()
}

/// Values per line and field width of a Fortran format such as `(8F10.5)`, `(10I8)` or
/// `(5E15.7)`.
pub(crate) fn fortran_format(spec: &str) -> Option<(usize, usize)> {
    let s: String = spec
        .chars()
        .filter(|c| !c.is_whitespace() && *c != '(' && *c != ')')
        .collect::<String>()
        .to_ascii_uppercase();
    let pos = s.find(['F', 'E', 'I', 'G', 'D'])?;
    let count: usize = if pos == 0 { 1 } else { s[..pos].parse().ok()? };
    let rest = &s[pos + 1..];
    let width: usize = rest.split('.').next()?.parse().ok()?;
    (count > 0 && width > 0).then_some((count, width))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fortran_runs_split() {
        assert_eq!(
            split_free(" 2.3489E-2-1.6646E-2 7.7538E-3"),
            vec!["2.3489E-2", "-1.6646E-2", "7.7538E-3"]
        );
        assert_eq!(
            split_free("-.000011 -.000011  .000001"),
            vec!["-.000011", "-.000011", ".000001"]
        );
        assert_eq!(
            split_fixed(" 2.3489E-2-1.6646E-2", 10),
            vec!["2.3489E-2", "-1.6646E-2"]
        );
        assert_eq!(fortran_format("(8F10.5)"), Some((8, 10)));
        assert_eq!(fortran_format("( 10I8 )"), Some((10, 8)));
        assert_eq!(parse_number("1.5D-3"), Ok(1.5e-3));
        assert!(parse_number("nan").is_err());
        assert!(parse_number("1e999").is_err());
        assert!(parse_number("abc").is_err());
    }
}
