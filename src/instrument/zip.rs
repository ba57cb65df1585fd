//! The little of the ZIP format that .x3p and .xlsx files need: the central directory, and an
//! entry's bytes (stored or deflated), checked against the sizes and the CRC-32 the directory
//! gives. Sizes are checked against the archive's length before anything is allocated, and the
//! inflated size is capped by the directory's (deflate cannot expand beyond 1032:1).
//!
//! Layout (PKWARE APPNOTE, sections 4.3.7, 4.3.12, 4.3.16): an end-of-central-directory record
//! (signature `PK\x05\x06`) within the last 65 557 bytes gives the directory's offset and entry
//! count; each directory header (`PK\x01\x02`) gives an entry's method, CRC, sizes, name and the
//! offset of its local header (`PK\x03\x04`), after which the data follow. ZIP64 archives
//! (entries of 4 GiB and more) are refused with a message.

use std::path::Path;

use super::bad;
use crate::Error;

/// One entry of the central directory.
#[derive(Debug, Clone)]
pub(crate) struct Entry {
    pub(crate) name: String,
    method: u16,
    crc: u32,
    compressed: usize,
    size: usize,
    local_offset: usize,
}

/// A ZIP archive held in memory.
pub(crate) struct Archive<'a> {
    path: &'a Path,
    bytes: &'a [u8],
    pub(crate) entries: Vec<Entry>,
}

/// The local file header's signature, which every ZIP archive starts with.
pub(crate) const MAGIC: &[u8] = b"PK\x03\x04";

fn u16_at(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn u32_at(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

impl Entry {
    /// Uncompressed size, bytes.
    pub(crate) fn size(&self) -> usize {
        self.size
    }
}

impl<'a> Archive<'a> {
    /// Reads the central directory of the archive `bytes` (the content of `path`).
    pub(crate) fn open(path: &'a Path, bytes: &'a [u8]) -> Result<Self, Error> {
        let eocd = find_eocd(bytes).ok_or_else(|| {
            bad(
                path,
                "not a ZIP archive: no end-of-central-directory record (PK\\x05\\x06) in the \
                 last 65 557 bytes (truncated file?)",
            )
        })?;
        let count = u16_at(bytes, eocd + 10).unwrap_or(0) as usize;
        let dir_size = u32_at(bytes, eocd + 12).unwrap_or(0);
        let dir_offset = u32_at(bytes, eocd + 16).unwrap_or(0);
        if count == 0xffff || dir_size == u32::MAX || dir_offset == u32::MAX {
            return Err(bad(
                path,
                format!("byte {eocd}: ZIP64 archive (not supported; entries must be < 4 GiB)"),
            ));
        }
        let mut at = dir_offset as usize;
        if at
            .checked_add(dir_size as usize)
            .is_none_or(|end| end > eocd)
        {
            return Err(bad(
                path,
                format!(
                    "byte {eocd}: the central directory ({dir_size} bytes at byte {dir_offset}) \
                     does not end before the end record (truncated or corrupt ZIP)"
                ),
            ));
        }
        // A directory header has 46 fixed bytes: the count cannot exceed the space.
        let mut entries = Vec::with_capacity(count.min(dir_size as usize / 46));
        for _ in 0..count {
            let (entry, next) = read_dir_entry(path, bytes, at)?;
            entries.push(entry);
            at = next;
        }
        Ok(Archive {
            path,
            bytes,
            entries,
        })
    }

    /// The entry named `name` (exact, case-sensitive), if present.
    pub(crate) fn find(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// The uncompressed bytes of `entry`, checked against its size and CRC-32.
    pub(crate) fn extract(&self, entry: &Entry) -> Result<Vec<u8>, Error> {
        let at = entry.local_offset;
        let name = &entry.name;
        let truncated = || {
            bad(
                self.path,
                format!("byte {at}: local header of ZIP entry '{name}' is truncated"),
            )
        };
        if u32_at(self.bytes, at).ok_or_else(truncated)? != 0x0403_4b50 {
            return Err(bad(
                self.path,
                format!("byte {at}: expected a local header (PK\\x03\\x04) for ZIP entry '{name}'"),
            ));
        }
        let name_len = u16_at(self.bytes, at + 26).ok_or_else(truncated)? as usize;
        let extra_len = u16_at(self.bytes, at + 28).ok_or_else(truncated)? as usize;
        let start = at + 30 + name_len + extra_len;
        let data = start
            .checked_add(entry.compressed)
            .and_then(|end| self.bytes.get(start..end))
            .ok_or_else(|| {
                bad(
                    self.path,
                    format!(
                        "byte {start}: ZIP entry '{name}' needs {} bytes, the file ends at {} \
                         (truncated file?)",
                        entry.compressed,
                        self.bytes.len()
                    ),
                )
            })?;
        let out = match entry.method {
            0 => data.to_vec(),
            8 => {
                if entry.size / 1032 > entry.compressed {
                    return Err(bad(
                        self.path,
                        format!(
                            "byte {start}: ZIP entry '{name}' claims {} bytes from {} deflated \
                             (more than deflate's 1032:1 can give)",
                            entry.size, entry.compressed
                        ),
                    ));
                }
                miniz_oxide::inflate::decompress_to_vec_with_limit(data, entry.size).map_err(
                    |e| {
                        bad(
                            self.path,
                            format!("byte {start}: ZIP entry '{name}' does not inflate: {e:?}"),
                        )
                    },
                )?
            }
            m => {
                return Err(bad(
                    self.path,
                    format!(
                        "byte {at}: ZIP entry '{name}' uses compression method {m} \
                         (expected 0, stored, or 8, deflate)"
                    ),
                ));
            }
        };
        if out.len() != entry.size {
            return Err(bad(
                self.path,
                format!(
                    "byte {start}: ZIP entry '{name}' gave {} bytes, its directory says {}",
                    out.len(),
                    entry.size
                ),
            ));
        }
        let crc = crc32(&out);
        if crc != entry.crc {
            return Err(bad(
                self.path,
                format!(
                    "byte {start}: ZIP entry '{name}' has CRC-32 {crc:08x}, its directory says \
                     {:08x} (corrupt file)",
                    entry.crc
                ),
            ));
        }
        Ok(out)
    }

    /// The uncompressed bytes of the entry named `name`, or an error naming what is missing.
    pub(crate) fn extract_named(&self, name: &str, what: &str) -> Result<Vec<u8>, Error> {
        let entry = self.find(name).ok_or_else(|| {
            bad(
                self.path,
                format!("{what}: the archive has no entry '{name}'"),
            )
        })?;
        self.extract(entry)
    }
}

/// Offset of the end-of-central-directory record: the last `PK\x05\x06` whose comment length
/// reaches exactly the end of the file.
fn find_eocd(bytes: &[u8]) -> Option<usize> {
    let n = bytes.len();
    let lowest = n.saturating_sub(22 + 0xffff);
    (lowest..=n.checked_sub(22)?).rev().find(|&i| {
        bytes[i..i + 4] == *b"PK\x05\x06"
            && u16_at(bytes, i + 20).is_some_and(|c| i + 22 + c as usize == n)
    })
}

/// The directory header at `at`, and the offset of the next.
fn read_dir_entry(path: &Path, bytes: &[u8], at: usize) -> Result<(Entry, usize), Error> {
    let truncated = || {
        bad(
            path,
            format!("byte {at}: ZIP central directory header is truncated"),
        )
    };
    if u32_at(bytes, at).ok_or_else(truncated)? != 0x0201_4b50 {
        return Err(bad(
            path,
            format!("byte {at}: expected a central directory header (PK\\x01\\x02)"),
        ));
    }
    let field16 = |off: usize| u16_at(bytes, at + off).ok_or_else(truncated);
    let field32 = |off: usize| u32_at(bytes, at + off).ok_or_else(truncated);
    let method = field16(10)?;
    let crc = field32(16)?;
    let compressed = field32(20)?;
    let size = field32(24)?;
    let name_len = field16(28)? as usize;
    let extra_len = field16(30)? as usize;
    let comment_len = field16(32)? as usize;
    let local_offset = field32(42)?;
    if compressed == u32::MAX || size == u32::MAX || local_offset == u32::MAX {
        return Err(bad(
            path,
            format!("byte {at}: ZIP64 entry (not supported; entries must be < 4 GiB)"),
        ));
    }
    let name_bytes = bytes
        .get(at + 46..at + 46 + name_len)
        .ok_or_else(truncated)?;
    let entry = Entry {
        name: String::from_utf8_lossy(name_bytes).into_owned(),
        method,
        crc,
        compressed: compressed as usize,
        size: size as usize,
        local_offset: local_offset as usize,
    };
    Ok((entry, at + 46 + name_len + extra_len + comment_len))
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) as ZIP uses it.
fn crc32(data: &[u8]) -> u32 {
    const TABLE: [u32; 256] = {
        let mut t = [0u32; 256];
        let mut i = 0;
        while i < 256 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 8 {
                c = if c & 1 != 0 {
                    0xedb8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
                k += 1;
            }
            t[i] = c;
            i += 1;
        }
        t
    };
    !data.iter().fold(!0u32, |c, &b| {
        TABLE[((c ^ b as u32) & 0xff) as usize] ^ (c >> 8)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The standard check value of CRC-32/ISO-HDLC.
    #[test]
    fn crc32_check_value() {
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
    }
}
