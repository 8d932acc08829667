//! Every input file is read through one size limit, whatever its kind: a regular file's
//! size is known before it is read, but a device (`/dev/zero`), a fifo or a file growing
//! under the reader says nothing in advance, and a sparse file claims gigabytes it would
//! take seconds to read. At most `limit + 1` bytes are read (`Read::take`), and one more
//! than the limit refuses the file.

use std::io::Read;
use std::path::Path;

/// The largest file of a set a command reads back (`optimum.json`, a report's JSON files
/// and pictures): a study of a million starts writes a few megabytes.
pub const MAX_SET_FILE_BYTES: u64 = 64 << 20;

/// The bytes of the file at `path`, at most `limit` of them; `what` names the file in the
/// refusal of a larger one ("a problem file"). The error is a sentence without the path,
/// for the caller to place.
pub fn read_bytes(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>, String> {
    let mib = if limit.is_multiple_of(1 << 20) {
        format!(" ({} MiB)", limit >> 20)
    } else {
        String::new()
    };
    let too_large =
        |size: String| format!("the file has {size} bytes; {what} may have at most {limit}{mib}");
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read the file: {e}"))?;
    let meta = file
        .metadata()
        .map_err(|e| format!("cannot read the file: {e}"))?;
    // a regular file says its size: refused before a byte is read
    if meta.is_file() && meta.len() > limit {
        return Err(too_large(meta.len().to_string()));
    }
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(format!("more than {limit}")));
    }
    Ok(bytes)
}

/// [`read_bytes`] as UTF-8 text.
pub fn read_text(path: &Path, limit: u64, what: &str) -> Result<String, String> {
    String::from_utf8(read_bytes(path, limit, what)?)
        .map_err(|e| format!("cannot read the file: it is not UTF-8 text ({e})"))
}
