//! The checkpoint file around the state blocks (docs/outputs.md, "Checkpoints"):
//!
//! ```text
//! "DCFMCKP5"                       file format (8 bytes)
//! case fingerprint                 CaseFingerprint::to_bytes: field hashes, mesh hash
//! payload                          static block (if any), dynamic block, run driver's peaks
//! checksum                         u64 LE: FNV-1a 64 of every byte before it
//! ```
//!
//! The checksum catches a corrupted or cut file (any single changed byte changes it, see
//! [`crate::fnv`]); the fingerprint lets the resume say whether the case or its mesh
//! changed since the checkpoint was written ([`CaseFingerprint::changes_since`]). Older
//! formats (DCFMCKP4 and before, DCFMSTA1 first) had neither and are refused.

use std::io::Write;

use crate::case::fingerprint::CaseFingerprint;
use crate::error::{DcfmError, Result};
use crate::fnv::Fnv64;

/// Magic of the checkpoint file format this version writes and reads.
pub const FILE_MAGIC: &[u8; 8] = b"DCFMCKP5";

/// A writer that hashes everything written through it; [`SealedWriter::finish`] appends
/// the checksum.
pub struct SealedWriter<W: Write> {
    inner: W,
    hash: Fnv64,
}

impl<W: Write> SealedWriter<W> {
    /// Start a checkpoint file in `inner`: the magic and the fingerprint of the case.
    pub fn begin(inner: W, fingerprint: &CaseFingerprint) -> std::io::Result<Self> {
        let mut w = SealedWriter {
            inner,
            hash: Fnv64::new(),
        };
        w.write_all(FILE_MAGIC)?;
        w.write_all(&fingerprint.to_bytes())?;
        Ok(w)
    }

    /// Append the checksum of everything written and hand back the writer.
    pub fn finish(mut self) -> std::io::Result<W> {
        self.inner.write_all(&self.hash.finish().to_le_bytes())?;
        Ok(self.inner)
    }
}

impl<W: Write> Write for SealedWriter<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.hash.update(&buf[..n]);
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// A checkpoint file whose checksum matched.
#[derive(Debug)]
pub struct Sealed<'a> {
    /// What the checkpoint was written for.
    pub fingerprint: CaseFingerprint,
    /// The state blocks.
    pub payload: &'a [u8],
}

/// Check a checkpoint file's format and checksum and split it into fingerprint and
/// payload; `file` names it in errors.
pub fn open_checkpoint<'a>(bytes: &'a [u8], file: &str) -> Result<Sealed<'a>> {
    let err = |message: String| DcfmError::Parse {
        file: file.to_string(),
        message,
    };
    let again = "delete it or run without --resume to start again";
    let magic = bytes.get(..8).unwrap_or(bytes);
    if magic != FILE_MAGIC {
        let older = magic.len() == 8
            && (magic.starts_with(b"DCFMCKP") || magic.starts_with(b"DCFMSTA"))
            && magic.iter().all(|b| b.is_ascii_alphanumeric());
        return Err(err(if older {
            format!(
                "a checkpoint of an older dcfm (format {}, without checksum or case hash; this \
                 version reads {}): run without --resume to start again",
                String::from_utf8_lossy(magic),
                String::from_utf8_lossy(FILE_MAGIC)
            )
        } else {
            format!(
                "not a dcfm checkpoint (it does not start with {}): {again}",
                String::from_utf8_lossy(FILE_MAGIC)
            )
        }));
    }
    let Some(body_len) = bytes.len().checked_sub(8).filter(|&n| n >= 8) else {
        return Err(err(format!(
            "checkpoint cut short ({} bytes): {again}",
            bytes.len()
        )));
    };
    let (body, stored) = bytes.split_at(body_len);
    let stored = u64::from_le_bytes(stored.try_into().expect("8 bytes"));
    let mut h = Fnv64::new();
    h.update(body);
    if h.finish() != stored {
        return Err(err(format!(
            "checksum mismatch (stored {stored:016x}, computed {:016x}): the file is corrupted \
             or was cut short; {again}",
            h.finish()
        )));
    }
    let Some((fingerprint, used)) = CaseFingerprint::from_bytes(&body[8..]) else {
        return Err(err(format!("checkpoint header unreadable: {again}")));
    };
    Ok(Sealed {
        fingerprint,
        payload: &body[8 + used..],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sealed(payload: &[u8]) -> Vec<u8> {
        let mut fp = CaseFingerprint::default();
        fp.fields.insert("a.b".into(), 7);
        fp.mesh = 42;
        let mut w = SealedWriter::begin(Vec::new(), &fp).unwrap();
        w.write_all(payload).unwrap();
        w.finish().unwrap()
    }

    #[test]
    fn round_trip() {
        let bytes = sealed(b"state");
        let s = open_checkpoint(&bytes, "c.bin").unwrap();
        assert_eq!(s.payload, b"state");
        assert_eq!(s.fingerprint.mesh, 42);
        assert_eq!(s.fingerprint.fields["a.b"], 7);
    }

    #[test]
    fn every_single_bit_flip_is_refused() {
        let bytes = sealed(b"some state bytes");
        for bit in 0..8 * bytes.len() {
            let mut b = bytes.clone();
            b[bit / 8] ^= 1 << (bit % 8);
            let e = open_checkpoint(&b, "c.bin").unwrap_err().to_string();
            // A flip in the magic may even read as an older format ('5' → '4').
            let named = if bit < 64 {
                e.contains("not a dcfm checkpoint") || e.contains("older dcfm")
            } else {
                e.contains("checksum mismatch")
            };
            assert!(e.starts_with("c.bin: ") && named, "bit {bit}: {e}");
        }
    }

    #[test]
    fn old_and_foreign_files_are_named() {
        let e = open_checkpoint(b"DCFMCKP4\0\0\0\0\0\0\0\0", "c.bin")
            .unwrap_err()
            .to_string();
        assert!(e.contains("older dcfm (format DCFMCKP4"), "{e}");
        let e = open_checkpoint(b"DCFMSTA1....", "c.bin")
            .unwrap_err()
            .to_string();
        assert!(e.contains("older dcfm"), "{e}");
        let e = open_checkpoint(b"hello", "c.bin").unwrap_err().to_string();
        assert!(e.contains("not a dcfm checkpoint"), "{e}");
        let e = open_checkpoint(b"DCFMCKP5\x01", "c.bin")
            .unwrap_err()
            .to_string();
        assert!(e.contains("cut short"), "{e}");
    }
}
