//! Reading the values of an MSH 4.1 section, ASCII tokens or binary little-endian words,
//! with a bound on every count so that no input can make the reader allocate without limit.

/// How the numbers of the file are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Encoding {
    Ascii,
    /// Binary with `size_t` of this many bytes (4 or 8); `int` is 4 bytes, `double` 8.
    Binary {
        size_t: usize,
    },
}

/// A position in the file's bytes.
pub(super) struct Cursor<'a> {
    bytes: &'a [u8],
    pub(super) pos: usize,
    encoding: Encoding,
}

impl<'a> Cursor<'a> {
    pub(super) fn new(bytes: &'a [u8], pos: usize, encoding: Encoding) -> Self {
        Self {
            bytes,
            pos,
            encoding,
        }
    }

    /// Line number (1-based) of the current position, for messages.
    pub(super) fn line(&self) -> usize {
        self.line_at(self.pos)
    }

    /// Line number (1-based) of byte `pos`, for messages. It counts the newlines before
    /// `pos` (linear in the file), so it is called only once an error is being built:
    /// counting for every value read made the reader quadratic in the file size.
    fn line_at(&self, pos: usize) -> usize {
        self.bytes[..pos.min(self.bytes.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1
    }

    fn skip_space(&mut self) {
        while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// The next whitespace-delimited token (ASCII), or an error naming `what`.
    pub(super) fn token(&mut self, what: &str) -> Result<&'a str, String> {
        self.skip_space();
        let start = self.pos;
        while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(format!("end of file where {what} was expected"));
        }
        std::str::from_utf8(&self.bytes[start..self.pos])
            .map_err(|_| format!("{what}: not text (line {})", self.line()))
    }

    fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], String> {
        if self.bytes.len() - self.pos.min(self.bytes.len()) < n {
            return Err(format!("end of file where {what} was expected"));
        }
        let s = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    fn ascii<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, String> {
        let start = self.pos;
        let t = self.token(what)?;
        t.parse().map_err(|_| {
            let line = self.line_at(start);
            format!("{what}: '{t}' is not a valid number (line {line})")
        })
    }

    /// A `size_t` (count or tag).
    pub(super) fn size(&mut self, what: &str) -> Result<u64, String> {
        match self.encoding {
            Encoding::Ascii => self.ascii(what),
            Encoding::Binary { size_t: 8 } => {
                let b = self.take(8, what)?;
                Ok(u64::from_le_bytes(b.try_into().expect("8 bytes")))
            }
            Encoding::Binary { .. } => {
                let b = self.take(4, what)?;
                Ok(u32::from_le_bytes(b.try_into().expect("4 bytes")) as u64)
            }
        }
    }

    /// An `int` (entity tag, dimension, element type, physical tag).
    pub(super) fn int(&mut self, what: &str) -> Result<i32, String> {
        match self.encoding {
            Encoding::Ascii => self.ascii(what),
            Encoding::Binary { .. } => {
                let b = self.take(4, what)?;
                Ok(i32::from_le_bytes(b.try_into().expect("4 bytes")))
            }
        }
    }

    /// A `double`.
    pub(super) fn float(&mut self, what: &str) -> Result<f64, String> {
        match self.encoding {
            Encoding::Ascii => self.ascii(what),
            Encoding::Binary { .. } => {
                let b = self.take(8, what)?;
                Ok(f64::from_le_bytes(b.try_into().expect("8 bytes")))
            }
        }
    }

    /// A count of items that each take at least `min_bytes` in the file: larger than what
    /// the rest of the file could hold is an error (so nothing is allocated for it).
    pub(super) fn count(&mut self, what: &str, min_bytes: usize) -> Result<usize, String> {
        let start = self.pos;
        let n = self.size(what)?;
        let room = (self.bytes.len() - self.pos.min(self.bytes.len())) / min_bytes.max(1);
        if n > room as u64 {
            let line = self.line_at(start);
            return Err(format!(
                "{what} = {n} (line {line}): more than the rest of the file can hold"
            ));
        }
        Ok(n as usize)
    }

    /// Smallest number of bytes one `size_t` / `int` / `double` takes.
    pub(super) fn min_bytes(&self, kind: Kind) -> usize {
        match (self.encoding, kind) {
            (Encoding::Ascii, _) => 2,
            (Encoding::Binary { size_t }, Kind::Size) => size_t,
            (Encoding::Binary { .. }, Kind::Int) => 4,
            (Encoding::Binary { .. }, Kind::Float) => 8,
        }
    }

    /// Skip whitespace and expect the line `$End<name>`.
    pub(super) fn expect_end(&mut self, name: &str) -> Result<(), String> {
        self.skip_space();
        let tag = format!("$End{name}");
        if self.bytes[self.pos.min(self.bytes.len())..].starts_with(tag.as_bytes()) {
            self.pos += tag.len();
            Ok(())
        } else {
            Err(format!(
                "${name}: expected {tag} at line {} (the section holds more or fewer values than its counts say)",
                self.line()
            ))
        }
    }

    /// Skip whitespace and read a `$Section` header; `None` at the end of the file.
    pub(super) fn section(&mut self) -> Result<Option<&'a str>, String> {
        self.skip_space();
        if self.pos >= self.bytes.len() {
            return Ok(None);
        }
        let start = self.pos;
        let t = self.token("a section header")?;
        match t.strip_prefix('$') {
            Some(name) if !name.is_empty() => Ok(Some(name)),
            _ => Err(format!(
                "line {}: expected a section header such as $Nodes, found '{}'",
                self.line_at(start),
                t.chars().take(40).collect::<String>()
            )),
        }
    }

    /// Skip an unknown section up to and including `$End<name>`.
    pub(super) fn skip_section(&mut self, name: &str) -> Result<(), String> {
        let tag = format!("$End{name}");
        let rest = &self.bytes[self.pos.min(self.bytes.len())..];
        match rest.windows(tag.len()).position(|w| w == tag.as_bytes()) {
            Some(p) => {
                self.pos += p + tag.len();
                Ok(())
            }
            None => Err(format!("${name} without {tag}")),
        }
    }

    /// The raw text up to `$End<name>` (for the always-ASCII `$PhysicalNames`).
    pub(super) fn text_until_end(&mut self, name: &str) -> Result<&'a str, String> {
        let start = self.pos.min(self.bytes.len());
        self.skip_section(name)?;
        let end = self.pos - name.len() - 4;
        std::str::from_utf8(&self.bytes[start..end]).map_err(|_| format!("${name} is not text"))
    }

    /// Consume the rest of a header line and its newline: binary data starts right after
    /// it, and its first byte may well look like whitespace.
    pub(super) fn end_of_header_line(&mut self) {
        while self.pos < self.bytes.len() && self.bytes[self.pos] != b'\n' {
            self.pos += 1;
        }
        self.pos = (self.pos + 1).min(self.bytes.len());
    }
}

/// Kinds of stored numbers, for [`Cursor::min_bytes`].
#[derive(Clone, Copy, Debug)]
pub(super) enum Kind {
    Size,
    Int,
    Float,
}
