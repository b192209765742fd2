//! The temporary files an atomic write makes beside its target, and the one rule that removes
//! those a killed writer left behind, shared with mazesim's Python writer (`mazesim._atomic`):
//! the temporary of a target `NAME` is `.NAME.<pid>-<8 hex digits>.tmp` in the target's folder
//! (a long `NAME` cut and marked with `~` and 16 hex digits of its FNV-1a hash, so that the name
//! fits the 255-byte limit); the next write of the target, from either writer, removes each
//! temporary of that name made by a process that no longer runs, or by this process outside a
//! write still in progress. Nothing else in the folder is touched.
//!
//! Older versions of the core named their temporaries `.NAME.tmp-<pid>-<count>` (a long `NAME`
//! cut shorter, at [`OLD_ADDED`] bytes): those are removed under the same rule, by the pid
//! their names carry.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

/// The longest file name, in bytes, of the usual file systems (ext4, XFS, APFS, NTFS).
pub(crate) const NAME_MAX: usize = 255;
/// Bytes a temporary name adds to its stem: the dot before it, `.<10 digits>-<8 hex>.tmp`, and
/// room for a suffix of up to 8 bytes (as the Python writer reserves).
const ADDED: usize = 1 + 1 + 10 + 1 + 8 + 4 + 8;
const SUFFIX: &str = ".tmp";
/// Bytes the older core's temporary names (`.NAME.tmp-<pid>-<count>`) added to their stem: the
/// dot before it, `.tmp-`, 10 digits of pid, `-` and 20 digits of count.
const OLD_ADDED: usize = 1 + 5 + 10 + 1 + 20;

/// Temporary files made by this process so far: each write has its own, even when several
/// threads write the same path at once.
static TEMPORARY_FILES: AtomicU64 = AtomicU64::new(0);
/// The temporary files this process is writing now, by file name (a name holds the writer's
/// pid and a token of its own): the core's and, through [`set_writing`], the Python writer's,
/// so that neither writer of a process takes the other's write in progress for an orphan.
static WRITING: Mutex<Option<HashSet<String>>> = Mutex::new(None);

/// The part of a temporary name taken from the target's name: the name itself, or when the
/// temporary name would pass [`NAME_MAX`] bytes, its start (cut at a character boundary) and
/// `~` with 16 hex digits of the FNV-1a hash of the whole name.
pub(crate) fn temporary_stem(name: &str) -> String {
    stem_within(name, ADDED)
}

/// The stem of `name` in a temporary name that adds `added` bytes to it (see
/// [`temporary_stem`]).
fn stem_within(name: &str, added: usize) -> String {
    if name.len() + added <= NAME_MAX {
        return name.to_string();
    }
    let hash = crate::fingerprint::fnv1a(name.as_bytes());
    let mut room = NAME_MAX - added - 1 - 16;
    while !name.is_char_boundary(room) {
        room -= 1;
    }
    format!("{}~{hash:016x}", &name[..room])
}

/// A temporary file being written: its path is known to be in use by this process until it is
/// dropped (renamed over its target or removed).
pub(crate) struct Temporary {
    pub(crate) path: PathBuf,
}

impl Temporary {
    /// A fresh temporary path for the file `name` in `dir`, marked as being written.
    pub(crate) fn new(dir: &Path, name: &str) -> Temporary {
        let count = TEMPORARY_FILES.fetch_add(1, Ordering::Relaxed);
        // 8 hex digits: the count mixed with the time, so that two runs of one pid differ.
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.subsec_nanos())
            .unwrap_or(0);
        let token = (crate::fingerprint::fnv1a(&count.to_le_bytes()) as u32) ^ nanos;
        let path = dir.join(format!(
            ".{}.{}-{token:08x}{SUFFIX}",
            temporary_stem(name),
            std::process::id()
        ));
        set_writing(&file_name(&path), true);
        Temporary { path }
    }
}

impl Drop for Temporary {
    fn drop(&mut self) {
        set_writing(&file_name(&self.path), false);
    }
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|name| name.to_string_lossy().into_owned())
        .unwrap_or_default()
}

fn writing<R>(f: impl FnOnce(&mut HashSet<String>) -> R) -> R {
    let mut guard = WRITING.lock().unwrap_or_else(|e| e.into_inner());
    f(guard.get_or_insert_with(HashSet::new))
}

/// Marks the temporary file `name` (a file name, no folder) as being written by this process
/// (`true`) or no longer (`false`): the Python writer's temporaries join the core's here.
pub fn set_writing(name: &str, now: bool) {
    writing(|set| {
        if now {
            set.insert(name.to_string());
        } else {
            set.remove(name);
        }
    });
}

/// Whether this process is writing the temporary file `name` now (either writer).
pub fn is_writing(name: &str) -> bool {
    writing(|set| set.contains(name))
}

/// Whether `s` is 1 to `most` digits (lower-case hex digits too when `hex`).
fn digits(s: &str, most: usize, hex: bool) -> bool {
    s.len() <= most
        && !s.is_empty()
        && s.chars().all(|c| {
            c.is_ascii_digit() || (hex && c.is_ascii_hexdigit() && !c.is_ascii_uppercase())
        })
}

/// The process id in `file`'s name when it is a temporary of the target `name`: of this
/// version's kind, or of the older core's (`.NAME.tmp-<pid>-<count>`).
fn writer_of(file: &str, name: &str) -> Option<u32> {
    let hidden = file.strip_prefix('.')?;
    if let Some(rest) = hidden
        .strip_prefix(stem_within(name, OLD_ADDED).as_str())
        .and_then(|r| r.strip_prefix(".tmp-"))
    {
        if let Some((pid, count)) = rest.split_once('-') {
            if digits(pid, 10, false) && digits(count, 20, false) {
                return pid.parse().ok();
            }
        }
    }
    let rest = hidden
        .strip_prefix(temporary_stem(name).as_str())?
        .strip_prefix('.')?
        .strip_suffix(SUFFIX)?;
    let (pid, token) = rest.split_once('-')?;
    if !digits(pid, 10, false) || token.len() != 8 || !digits(token, 8, true) {
        return None;
    }
    pid.parse().ok()
}

/// Whether no process `pid` runs (known on Unix only; false when unsure).
fn process_is_gone(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return false;
        };
        if pid <= 0 {
            return false;
        }
        // SAFETY: signal 0 only asks whether the process exists; nothing is sent.
        let answer = unsafe { libc::kill(pid, 0) };
        answer != 0 && std::io::Error::last_os_error().raw_os_error() == Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        false
    }
}

/// Removes the orphaned temporaries of the file `name` in `dir` (see the module's docs) and
/// returns them; a file that cannot be removed is left.
pub(crate) fn remove_orphans(dir: &Path, name: &str) -> Vec<PathBuf> {
    let mut removed = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return removed;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(pid) = file.to_str().and_then(|f| writer_of(f, name)) else {
            continue;
        };
        let path = entry.path();
        let orphaned = if pid == std::process::id() {
            !is_writing(&file_name(&path))
        } else {
            process_is_gone(pid)
        };
        if orphaned && std::fs::remove_file(&path).is_ok() {
            removed.push(path);
        }
    }
    removed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_temporary_name_is_recognised_with_its_writer_and_nothing_else_is() {
        let made = Temporary::new(Path::new("."), "maze.toml");
        let file = made.path.file_name().unwrap().to_str().unwrap().to_string();
        assert_eq!(writer_of(&file, "maze.toml"), Some(std::process::id()));
        assert_eq!(writer_of(&file, "other.toml"), None);
        assert_eq!(
            writer_of(".maze.toml.12-0123abcd.tmp", "maze.toml"),
            Some(12)
        );
        assert_eq!(writer_of(".maze.toml.12-0123ABCD.tmp", "maze.toml"), None);
        assert_eq!(writer_of("maze.toml", "maze.toml"), None);
        assert_eq!(writer_of(".maze.toml.x-0123abcd.tmp", "maze.toml"), None);
        // The older core's names, by their pid; nothing like them but not them.
        assert_eq!(writer_of(".maze.toml.tmp-12-0", "maze.toml"), Some(12));
        assert_eq!(
            writer_of(".maze.toml.tmp-12-18446744073709551615", "maze.toml"),
            Some(12)
        );
        assert_eq!(writer_of(".maze.toml.tmp-12-", "maze.toml"), None);
        assert_eq!(writer_of(".maze.toml.tmp-12-3x", "maze.toml"), None);
        assert_eq!(writer_of(".maze.toml.tmp-12", "maze.toml"), None);
        assert_eq!(writer_of(".other.toml.tmp-12-0", "maze.toml"), None);
    }

    #[test]
    fn the_older_cores_orphans_go_by_the_same_rule_and_a_running_writers_stay() {
        let dir = std::env::temp_dir().join(format!("mazesim-old-orphans-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // This process makes no temporary of the old kind: one with its pid is orphaned.
        let own = dir.join(format!(".maze.toml.tmp-{}-3", std::process::id()));
        // Process 1 (init) runs: its temporary may be a write in progress.
        let running = dir.join(".maze.toml.tmp-1-0");
        // A long name's old stem was cut shorter than today's.
        let long = "m".repeat(240);
        let cut = dir.join(format!(
            ".{}.tmp-{}-0",
            stem_within(&long, OLD_ADDED),
            std::process::id()
        ));
        for path in [&own, &running, &cut] {
            std::fs::write(path, b"half").unwrap();
        }
        assert_eq!(remove_orphans(&dir, "maze.toml"), vec![own.clone()]);
        assert_eq!(remove_orphans(&dir, &long), vec![cut.clone()]);
        assert!(running.exists() && !own.exists() && !cut.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn orphans_of_this_process_and_of_ended_ones_go_and_a_write_in_progress_stays() {
        let dir = std::env::temp_dir().join(format!("mazesim-orphans-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let in_progress = Temporary::new(&dir, "maze.toml");
        std::fs::write(&in_progress.path, b"new").unwrap();
        let left = dir.join(format!(".maze.toml.{}-00000001.tmp", std::process::id()));
        std::fs::write(&left, b"half").unwrap();
        let other = dir.join(".other.toml.1-00000001.tmp");
        std::fs::write(&other, b"not ours").unwrap();
        let removed = remove_orphans(&dir, "maze.toml");
        assert_eq!(removed, vec![left.clone()]);
        assert!(in_progress.path.exists() && other.exists() && !left.exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn long_names_are_cut_to_fit_the_name_limit() {
        let name = "é".repeat(200);
        let made = Temporary::new(Path::new("."), &name);
        let file = made.path.file_name().unwrap().to_str().unwrap().len();
        assert!(file + 8 <= NAME_MAX, "{file}");
    }
}
