//! Reading input files within a size bound, and writing files the user cares about without ever
//! leaving them half-written.

use std::io::{Read, Write};
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{Error, Location, Result};

/// Reads the bytes of `path` (`what` names it in errors: "the world file"), at most `limit` of
/// them: a longer file, or an endless one such as `/dev/zero`, is refused once `limit + 1` bytes
/// are read, before it can fill the memory.
pub fn read_limited(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>> {
    let io_err = |e: std::io::Error| Error::io(path, &format!("cannot read {what}"), &e);
    let file = std::fs::File::open(path).map_err(io_err)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io_err)?;
    if bytes.len() as u64 > limit {
        return Err(Error::Format {
            location: Location {
                source: path.display().to_string(),
                line: 1,
                column: 1,
            },
            field: "(file)".into(),
            message: format!("expected {what} of at most {limit} bytes, found more"),
        });
    }
    Ok(bytes)
}

/// Temporary files made by this process so far: each write has its own, even when several
/// threads write the same path at once.
static TEMPORARY_FILES: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path` through a temporary file of its own in the same folder, synced, then
/// renamed: a reader sees the old file or the new one whole, and two writers of one path (two
/// threads of one process too) never write into each other's temporary file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let io_err = |e: std::io::Error| Error::io(path, "cannot write the file", &e);
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path.file_name().ok_or_else(|| Error::Io {
        path: path.display().to_string(),
        message: "expected a file path, found a folder".into(),
        errno: None,
        reason: None,
    })?;
    let tmp = dir.join(format!(
        ".{}.tmp-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        TEMPORARY_FILES.fetch_add(1, Ordering::Relaxed)
    ));
    let result = (|| {
        let mut f = std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io_err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_longer_than_the_limit_is_a_format_error_naming_it() {
        let dir = std::env::temp_dir().join(format!("mazesim-read-limited-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("eleven.txt");
        std::fs::write(&path, b"01234567890").unwrap();
        assert_eq!(read_limited(&path, 11, "the text").unwrap().len(), 11);
        let error = read_limited(&path, 10, "the text").unwrap_err().to_string();
        assert!(error.contains("eleven.txt:1:1"), "{error}");
        assert!(
            error.contains("expected the text of at most 10 bytes, found more"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn threads_writing_one_file_at_once_each_write_it_whole() {
        let dir = std::env::temp_dir().join(format!("mazesim-write-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("world.toml");
        let contents: Vec<Vec<u8>> = (0..8u8).map(|k| vec![b'a' + k; 64 * 1024]).collect();
        std::thread::scope(|scope| {
            for content in &contents {
                let path = &path;
                scope.spawn(move || {
                    for _ in 0..25 {
                        write_atomic(path, content).unwrap();
                    }
                });
            }
        });
        let written = std::fs::read(&path).unwrap();
        assert!(contents.contains(&written), "the file mixes writes");
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|entry| entry.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("world.toml")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn an_endless_file_stops_at_the_limit() {
        let error = read_limited(Path::new("/dev/zero"), 1 << 20, "the world file").unwrap_err();
        assert!(matches!(error, Error::Format { .. }), "{error}");
        let error = crate::world::World::load(Path::new("/dev/zero")).unwrap_err();
        assert!(
            error.to_string().contains("at most 67108864 bytes"),
            "{error}"
        );
        let error = crate::wbt::WbtImport::load(Path::new("/dev/zero")).unwrap_err();
        assert!(
            error.to_string().contains("at most 268435456 bytes"),
            "{error}"
        );
    }
}
