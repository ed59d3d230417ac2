//! Paths a model file names, judged on their text: whether they stay inside the model's folder.

use std::path::{Component, Path, PathBuf};

/// Logs (`warn`) that the model file `model` names a `what` at `file` outside its own folder (an
/// absolute path, a `file:` URI, or `..` past the folder): the user asked for the model, and
/// should hear of what else it reads.
pub(super) fn note_outside(model: &Path, file: &Path, what: &str) {
    let folder = model.parent().unwrap_or(Path::new(""));
    if !lexical_absolute(file).starts_with(lexical_absolute(folder)) {
        tracing::warn!(
            "{}: reading its {what} {}, which is outside the model's folder",
            model.display(),
            file.display()
        );
    }
}

/// `path` made absolute against the working directory (an empty path is the working directory),
/// with `.` dropped and each `..` taking away the component before it — on the text alone, links
/// not followed: what "inside a folder" is judged on, for scenes and for models.
pub(crate) fn lexical_absolute(path: &Path) -> PathBuf {
    let absolute = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().map_or_else(|_| path.to_path_buf(), |cwd| cwd.join(path))
    };
    let mut out = PathBuf::new();
    for component in absolute.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir => {
                if !out.pop() {
                    out.push("..");
                }
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod path_tests {
    use super::*;

    #[test]
    fn lexical_absolute_climbs_out_with_dot_dot() {
        assert_eq!(lexical_absolute(Path::new("/a/b/../c/./d")), PathBuf::from("/a/c/d"));
        assert_eq!(lexical_absolute(Path::new("/a/b/../../../x")), PathBuf::from("/../x"));
        assert!(!lexical_absolute(Path::new("/s/scenes/../shared/x.obj")).starts_with("/s/scenes"));
        assert!(lexical_absolute(Path::new("/s/scenes/./sub/../x.obj")).starts_with("/s/scenes"));
        let cwd = std::env::current_dir().expect("a working directory");
        assert_eq!(lexical_absolute(Path::new("")), cwd);
        assert_eq!(lexical_absolute(Path::new("m/../t.png")), cwd.join("t.png"));
    }
}
