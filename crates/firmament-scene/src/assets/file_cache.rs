//! What was made from files, kept while the files stay as they were: a scene is converted again
//! for every frame of a time-lapse and every edit in the viewer, and decoding its images each
//! time (a 2048 × 1024 albedo map: tens of milliseconds) would cost more than drawing the frame.
//!
//! An entry is found by its files' paths, lengths and modification times, so a file written
//! again is read again. Scenes read under a [`Confinement`](super::Confinement) (untrusted
//! mode) are never served from the cache: their limits apply to every read.

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::SystemTime;

/// A file as it was when read: its path, length (bytes) and modification time.
#[derive(Debug, Clone, PartialEq, Eq)]
struct FileStamp {
    path: PathBuf,
    len: u64,
    modified: SystemTime,
}

impl FileStamp {
    /// The file at `path` now; `None` where its metadata cannot be read (the loader then
    /// reports why).
    fn of(path: &Path) -> Option<Self> {
        let metadata = std::fs::metadata(path).ok()?;
        Some(Self {
            path: path.to_path_buf(),
            len: metadata.len(),
            modified: metadata.modified().ok()?,
        })
    }
}

/// One thing made from files.
struct Entry<T> {
    files: Vec<FileStamp>,
    value: Arc<T>,
    bytes: usize,
}

/// The last few things made from files, at most [`FileCache::MAX_ENTRIES`] of them and
/// [`FileCache::MAX_BYTES`] together (the oldest go first).
pub(crate) struct FileCache<T> {
    entries: Mutex<Vec<Entry<T>>>,
}

impl<T> FileCache<T> {
    /// Entries kept.
    pub(crate) const MAX_ENTRIES: usize = 8;
    /// Bytes kept, as the makers count them: 256 MiB.
    pub(crate) const MAX_BYTES: usize = 256 << 20;

    /// An empty cache.
    pub(crate) const fn new() -> Self {
        Self {
            entries: Mutex::new(Vec::new()),
        }
    }

    /// What `make` makes of the files at `paths`: kept from an earlier call while every file has
    /// the same length and modification time, else made now (and kept if `cacheable`, with its
    /// size in bytes from `size_of`). Errors are never kept.
    pub(crate) fn get_or_make<E>(
        &self,
        paths: &[&Path],
        cacheable: bool,
        size_of: impl FnOnce(&T) -> usize,
        make: impl FnOnce() -> Result<T, E>,
    ) -> Result<Arc<T>, E> {
        let files: Option<Vec<FileStamp>> = paths.iter().map(|p| FileStamp::of(p)).collect();
        let Some(files) = files.filter(|_| cacheable) else {
            return make().map(Arc::new);
        };
        if let Some(entry) = self.lock().iter().find(|e| e.files == files) {
            return Ok(entry.value.clone());
        }
        let value = Arc::new(make()?);
        let bytes = size_of(&value);
        if bytes <= Self::MAX_BYTES {
            let mut entries = self.lock();
            entries.retain(|e| e.files.iter().all(|f| !files.iter().any(|g| g.path == f.path)));
            entries.push(Entry {
                files,
                value: value.clone(),
                bytes,
            });
            while entries.len() > Self::MAX_ENTRIES || entries.iter().map(|e| e.bytes).sum::<usize>() > Self::MAX_BYTES
            {
                entries.remove(0);
            }
        }
        Ok(value)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<Entry<T>>> {
        self.entries.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use super::*;

    fn write(path: &Path, contents: &[u8]) {
        std::fs::write(path, contents).expect("write a test file");
    }

    #[test]
    fn a_file_is_made_once_until_it_changes() {
        let folder = tempfile::tempdir().expect("a temporary folder");
        let path = folder.path().join("map.bin");
        write(&path, b"one");
        let cache = FileCache::<usize>::new();
        let made = Cell::new(0);
        let make = || -> Result<usize, String> {
            made.set(made.get() + 1);
            Ok(std::fs::read(&path).map_err(|e| e.to_string())?.len())
        };
        assert_eq!(*cache.get_or_make(&[&path], true, |_| 1, make).unwrap(), 3);
        assert_eq!(*cache.get_or_make(&[&path], true, |_| 1, make).unwrap(), 3);
        assert_eq!(made.get(), 1, "the second call is served from the cache");
        // Written again with another length: read again, and the old entry replaced.
        write(&path, b"three");
        assert_eq!(*cache.get_or_make(&[&path], true, |_| 1, make).unwrap(), 5);
        assert_eq!(made.get(), 2);
        assert_eq!(cache.lock().len(), 1);
        // Not cacheable (a confined scene): made every time.
        cache.get_or_make(&[&path], false, |_| 1, make).unwrap();
        assert_eq!(made.get(), 3);
    }

    #[test]
    fn errors_and_missing_files_are_not_kept() {
        let folder = tempfile::tempdir().expect("a temporary folder");
        let path = folder.path().join("missing.png");
        let cache = FileCache::<u8>::new();
        let failing = || -> Result<u8, &str> { Err("cannot read") };
        assert!(cache.get_or_make(&[&path], true, |_| 1, failing).is_err());
        write(&path, b"x");
        assert!(cache.get_or_make(&[&path], true, |_| 1, failing).is_err());
        assert!(cache.lock().is_empty());
    }

    #[test]
    fn the_oldest_entries_go_past_the_limits() {
        let folder = tempfile::tempdir().expect("a temporary folder");
        let cache = FileCache::<usize>::new();
        let paths: Vec<PathBuf> = (0..=FileCache::<usize>::MAX_ENTRIES)
            .map(|i| folder.path().join(format!("{i}.bin")))
            .collect();
        for (i, path) in paths.iter().enumerate() {
            write(path, b"x");
            cache.get_or_make(&[path], true, |_| 1, || Ok::<_, ()>(i)).unwrap();
        }
        let kept = cache.lock().iter().map(|e| *e.value).collect::<Vec<_>>();
        assert_eq!(kept, (1..=FileCache::<usize>::MAX_ENTRIES).collect::<Vec<_>>());
        // One entry as large as the budget pushes out every other.
        let big = &paths[0];
        cache
            .get_or_make(&[big], true, |_| FileCache::<usize>::MAX_BYTES, || Ok::<_, ()>(0))
            .unwrap();
        assert_eq!(cache.lock().len(), 1);
    }
}
