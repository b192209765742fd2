//! Reading input files within a size bound, and writing files the user cares about without ever
//! leaving them half-written.
//!
//! Inputs are regular files only: a file is opened without waiting (a FIFO no process writes to
//! would block the open for ever) and a folder, FIFO, device or socket is refused before a byte
//! is read. Outputs follow what the path names, as mazesim's Python writer does: a regular file
//! (or a new path) is replaced atomically, through its symbolic links (the link stays); a device,
//! FIFO or terminal, or a path through `/proc` (`/dev/stdout`), is written into, never replaced;
//! a folder or a socket is refused. Temporary names fit the 255-byte limit of a file name.

use std::fs::{File, FileType, OpenOptions};
use std::io::{ErrorKind, Read, Write};
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};

/// The error number a refused kind of file carries (`EINVAL`: not a file that can be used).
const NOT_A_FILE: i32 = 22;

/// What a file that is not a regular file is, in words.
fn kind_of(kind: FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return "a FIFO (named pipe)";
        }
        if kind.is_char_device() {
            return "a character device";
        }
        if kind.is_block_device() {
            return "a block device";
        }
        if kind.is_socket() {
            return "a socket";
        }
    }
    if kind.is_dir() {
        "a folder"
    } else {
        "not a regular file"
    }
}

/// The error of a file refused for what it is, or for what the OS said.
fn refused(path: &Path, what: &str, reason: String) -> Error {
    Error::Io {
        path: path.display().to_string(),
        message: format!("{what}: {reason}"),
        errno: Some(NOT_A_FILE),
        reason: Some(reason),
    }
}

/// `options` made not to wait when the file opened is a FIFO (no effect on other files).
fn without_waiting(options: &mut OpenOptions) -> &mut OpenOptions {
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    options
}

/// Opens `path` for reading, if it is a regular file (see the module's docs).
fn open_regular(path: &Path, what: &str) -> Result<File> {
    let io_err = |e: std::io::Error| Error::io(path, &format!("cannot read {what}"), &e);
    let file = without_waiting(OpenOptions::new().read(true))
        .open(path)
        .map_err(io_err)?;
    let kind = file.metadata().map_err(io_err)?.file_type();
    if !kind.is_file() {
        return Err(refused(
            path,
            &format!("cannot read {what}"),
            format!("expected a regular file, found {}", kind_of(kind)),
        ));
    }
    Ok(file)
}

/// Reads the bytes of `path` (`what` names it in errors: "the world file"), at most `limit` of
/// them: a regular file only (see the module's docs); a longer one is refused once `limit + 1`
/// bytes are read, before it can fill the memory.
pub fn read_limited(path: &Path, limit: u64, what: &str) -> Result<Vec<u8>> {
    let io_err = |e: std::io::Error| Error::io(path, &format!("cannot read {what}"), &e);
    let file = open_regular(path, what)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(io_err)?;
    if bytes.len() as u64 > limit {
        return Err(too_long(&path.display().to_string(), what, limit, "more"));
    }
    Ok(bytes)
}

/// Reads `path` as UTF-8 text with [`read_limited`]'s bounds; text that is not UTF-8 is an I/O
/// error naming the file.
pub fn read_text_limited(path: &Path, limit: u64, what: &str) -> Result<String> {
    let bytes = read_limited(path, limit, what)?;
    String::from_utf8(bytes).map_err(|error| {
        let found = other_encoding(error.as_bytes(), error.utf8_error().valid_up_to());
        let not_text = std::io::Error::new(
            ErrorKind::InvalidData,
            format!(
                "expected UTF-8 text, found {found}: save it as UTF-8 (an editor's \"Save as\", \
                 encoding UTF-8) and give it again"
            ),
        );
        Error::io(path, &format!("cannot read {what}"), &not_text)
    })
}

/// What a text that is not UTF-8 looks like, from where its decoding failed (`at`): UTF-16 by
/// its byte-order mark (Windows Notepad's "Unicode"), else the first byte that is not UTF-8.
fn other_encoding(bytes: &[u8], at: usize) -> String {
    match bytes {
        [0xFF, 0xFE, ..] | [0xFE, 0xFF, ..] if at < 2 => format!(
            "UTF-16 text (it starts with the byte-order mark {:02X} {:02X})",
            bytes[0], bytes[1]
        ),
        _ => format!(
            "a byte 0x{:02X} that is not UTF-8 (text in another encoding, such as Latin-1 or \
             Windows-1252?)",
            bytes.get(at).copied().unwrap_or_default()
        ),
    }
}

/// The text a TOML reader parses: CRLF line ends read as LF, since TOML takes either as a
/// newline and the `toml` crate kept the CR inside a multi-line string (a world saved by a
/// Windows editor held a grid map with a CR on every row, unequal to the same map with LF, and
/// saved those CRs back). Lines and columns are unchanged, so errors point where they did.
pub fn toml_text(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains("\r\n") {
        std::borrow::Cow::Owned(text.replace("\r\n", "\n"))
    } else {
        std::borrow::Cow::Borrowed(text)
    }
}

/// Refuses a text given in memory (not read from a file) longer than the bound of the file it
/// stands for, before it is parsed: a parser's memory is a multiple of its input, and a text of a
/// few hundred MB made it ask for more than the process may have (an abort, not an error).
pub fn check_text_length(text: &str, source: &str, limit: u64, what: &str) -> Result<()> {
    if text.len() as u64 > limit {
        let found = format!("{} bytes", text.len());
        return Err(too_long(source, what, limit, &found));
    }
    Ok(())
}

/// The format error of an input of more than `limit` bytes (`found`: how many, or "more").
fn too_long(source: &str, what: &str, limit: u64, found: &str) -> Error {
    let message = format!("expected {what} of at most {limit} bytes, found {found}");
    Error::format_at(source, 1, 1, "(file)", message)
}

/// How an output path is written.
enum Output {
    /// Replaced atomically: the regular file (existing or not) the path leads to.
    File(PathBuf),
    /// Written into: a device, FIFO, terminal or a path through `/proc`.
    Stream,
}

/// The paths a chain of symbolic links goes through from `path` (itself first), at most 40.
fn link_chain(path: &Path) -> Vec<PathBuf> {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut chain = vec![absolute];
    while chain.len() <= 40 {
        let last = &chain[chain.len() - 1];
        let Ok(next) = std::fs::read_link(last) else {
            break;
        };
        let joined = last.parent().unwrap_or(Path::new("/")).join(next);
        chain.push(std::path::absolute(&joined).unwrap_or(joined));
    }
    chain
}

/// What `path` names, and so how it is written (see the module's docs).
fn output_of(path: &Path) -> Result<Output> {
    let what = "cannot write the file";
    let chain = link_chain(path);
    if chain.iter().any(|step| step.starts_with("/proc")) {
        return Ok(Output::Stream);
    }
    let kind = match std::fs::metadata(path) {
        Ok(metadata) => metadata.file_type(),
        // Nothing there yet: the file the last link names (the path itself without links).
        Err(e) if e.kind() == ErrorKind::NotFound => {
            return Ok(Output::File(chain[chain.len() - 1].clone()));
        }
        Err(e) => return Err(Error::io(path, what, &e)),
    };
    if kind.is_file() {
        let real = std::fs::canonicalize(path).map_err(|e| Error::io(path, what, &e))?;
        return Ok(Output::File(real));
    }
    if kind.is_dir() {
        return Err(refused(path, what, "it is a folder".into()));
    }
    #[cfg(unix)]
    if std::os::unix::fs::FileTypeExt::is_socket(&kind) {
        return Err(refused(
            path,
            what,
            "expected a file, a device or a FIFO, found a socket".into(),
        ));
    }
    Ok(Output::Stream)
}

/// Whether writing `path` replaces a regular file (existing or new) rather than writing into a
/// device, FIFO, terminal or a path through `/proc` (see the module's docs).
pub fn replaces_a_file(path: &Path) -> Result<bool> {
    Ok(matches!(output_of(path)?, Output::File(_)))
}

/// Writes `bytes` into the device, FIFO or terminal `path`, appending; a FIFO no process reads
/// is refused at once instead of waited on.
fn write_stream(path: &Path, bytes: &[u8]) -> Result<()> {
    let what = "cannot write the file";
    let mut file = without_waiting(OpenOptions::new().append(true))
        .open(path)
        .map_err(|e| {
            #[cfg(unix)]
            if e.raw_os_error() == Some(libc::ENXIO) {
                return refused(
                    path,
                    what,
                    "it is a FIFO that no process reads (start its reader first)".into(),
                );
            }
            Error::io(path, what, &e)
        })?;
    let mut rest = bytes;
    while !rest.is_empty() {
        match file.write(rest) {
            Ok(0) => return Err(Error::io(path, what, &ErrorKind::WriteZero.into())),
            Ok(written) => rest = &rest[written..],
            // The descriptor does not wait: a full pipe is waited on here.
            Err(e) if e.kind() == ErrorKind::WouldBlock => {
                std::thread::sleep(std::time::Duration::from_millis(1));
            }
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(e) => return Err(Error::io(path, what, &e)),
        }
    }
    Ok(())
}

/// Writes `bytes` to `path` as the module's docs say: a regular file through a temporary file
/// of its own in the same folder, synced, then renamed (a reader sees the old file or the new
/// one whole, and two writers of one path, two threads of one process too, never write into
/// each other's temporary file); a device, FIFO or terminal by writing into it. Errors name
/// `path` as given, never the temporary file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let target = match output_of(path)? {
        Output::Stream => return write_stream(path, bytes),
        Output::File(target) => target,
    };
    let io_err = |e: std::io::Error| Error::io(path, "cannot write the file", &e);
    let dir = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = target.file_name().ok_or_else(|| Error::Io {
        path: path.display().to_string(),
        message: "expected a file path, found a folder".into(),
        errno: None,
        reason: None,
    })?;
    let name = name.to_string_lossy();
    // The file it replaces keeps its permissions (a private file stays private); one that
    // nobody may write is refused, as a plain write of it would be.
    let kept = std::fs::metadata(&target).ok().filter(|m| m.is_file());
    if kept.as_ref().is_some_and(|m| m.permissions().readonly()) {
        return Err(refused(
            path,
            "cannot write the file",
            "it is read-only (make it writable, or save under another name)".into(),
        ));
    }
    crate::temporary_files::remove_orphans(dir, &name);
    let temporary = crate::temporary_files::Temporary::new(dir, &name);
    let tmp = &temporary.path;
    let result = (|| {
        let mut f = OpenOptions::new().write(true).create_new(true).open(tmp)?;
        f.write_all(bytes)?;
        if let Some(old) = &kept {
            f.set_permissions(old.permissions())?;
        }
        f.sync_all()?;
        std::fs::rename(tmp, &target)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(tmp);
    }
    result.map_err(io_err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_toml_text_reads_crlf_line_ends_as_lf() {
        let windows = "map = \"\"\"\r\n+--+\r\n|  |\r\n\"\"\"\r\n";
        assert_eq!(toml_text(windows), "map = \"\"\"\n+--+\n|  |\n\"\"\"\n");
        assert!(matches!(
            toml_text("a = 1\n"),
            std::borrow::Cow::Borrowed(_)
        ));
        // A lone CR is no line end of TOML's: left for the parser to refuse.
        assert_eq!(toml_text("a = 1\rb = 2"), "a = 1\rb = 2");
    }

    #[test]
    fn a_text_longer_than_its_files_bound_is_refused_saying_both_lengths() {
        assert!(check_text_length("0123456789", "<string>", 10, "the text").is_ok());
        let error = check_text_length("0123456789!", "<string>", 10, "the text").unwrap_err();
        let message = error.to_string();
        assert!(message.starts_with("<string>:1:1"), "{message}");
        assert!(
            message.contains("expected the text of at most 10 bytes, found 11 bytes"),
            "{message}"
        );
    }

    #[test]
    fn a_text_in_another_encoding_names_it_and_says_to_save_it_as_utf8() {
        let dir =
            std::env::temp_dir().join(format!("mazesim-read-encoding-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let cases: [(&str, &[u8], &str); 3] = [
            (
                "utf16.toml",
                b"\xFF\xFEa\x00",
                "UTF-16 text (it starts with the byte-order mark FF FE)",
            ),
            ("utf16be.toml", b"\xFE\xFF\x00a", "byte-order mark FE FF"),
            (
                "latin1.toml",
                b"# fl\xE8che\n",
                "a byte 0xE8 that is not UTF-8",
            ),
        ];
        for (name, bytes, found) in cases {
            let path = dir.join(name);
            std::fs::write(&path, bytes).unwrap();
            let error = read_text_limited(&path, 100, "the world file")
                .unwrap_err()
                .to_string();
            assert!(error.contains(found), "{error}");
            assert!(error.contains("save it as UTF-8"), "{error}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

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
    fn only_regular_files_are_read_and_a_fifo_without_writer_does_not_wait() {
        let dir = std::env::temp_dir().join(format!("mazesim-read-kinds-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("world.fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        let mut refused_paths = vec![
            (PathBuf::from("/dev/zero"), "a character device"),
            (dir.clone(), "a folder"),
        ];
        if made.is_ok_and(|status| status.success()) {
            refused_paths.push((fifo, "a FIFO (named pipe)"));
        }
        for (path, kind) in refused_paths {
            for error in [
                read_limited(&path, 1 << 20, "the world file").unwrap_err(),
                crate::world::World::load(&path).unwrap_err(),
                crate::wbt::WbtImport::load(&path).unwrap_err(),
            ] {
                let text = error.to_string();
                assert!(matches!(error, Error::Io { .. }), "{text}");
                assert!(
                    text.contains(&format!("expected a regular file, found {kind}")),
                    "{text}"
                );
            }
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn outputs_that_are_not_regular_files_are_written_into_not_replaced() {
        let dir = std::env::temp_dir().join(format!("mazesim-write-kinds-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // A link to /dev/null: written through, the link kept, /dev/null a device still.
        let link = dir.join("null.toml");
        std::os::unix::fs::symlink("/dev/null", &link).unwrap();
        write_atomic(&link, b"name = 'x'\n").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        use std::os::unix::fs::FileTypeExt;
        assert!(std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device());
        // A link to a regular file: the file is replaced, the link stays.
        let real = dir.join("real.toml");
        std::fs::write(&real, b"old").unwrap();
        let to_real = dir.join("to-real.toml");
        std::os::unix::fs::symlink(&real, &to_real).unwrap();
        write_atomic(&to_real, b"new").unwrap();
        assert_eq!(std::fs::read(&real).unwrap(), b"new");
        assert!(std::fs::symlink_metadata(&to_real)
            .unwrap()
            .file_type()
            .is_symlink());
        // A FIFO no process reads: refused at once.
        let fifo = dir.join("out.fifo");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let error = write_atomic(&fifo, b"x").unwrap_err().to_string();
            assert!(error.contains("FIFO that no process reads"), "{error}");
            assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
        }
        // A full disk names the user's file.
        let error = write_atomic(Path::new("/dev/full"), b"x")
            .unwrap_err()
            .to_string();
        assert_eq!(
            error,
            "/dev/full: cannot write the file: No space left on device"
        );
        // A folder is refused.
        let error = write_atomic(&dir, b"x").unwrap_err().to_string();
        assert!(
            error.ends_with("cannot write the file: it is a folder"),
            "{error}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn names_up_to_the_file_system_limit_are_written() {
        let dir = std::env::temp_dir().join(format!("mazesim-long-names-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for length in [200, 236, 250, 255] {
            let name = format!(
                "{}{}.toml",
                "é".repeat((length - 5) / 2),
                "x".repeat((length - 5) % 2)
            );
            assert_eq!(name.len(), length);
            write_atomic(&dir.join(&name), b"whole").unwrap();
            assert_eq!(std::fs::read(dir.join(&name)).unwrap(), b"whole");
        }
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 4);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
