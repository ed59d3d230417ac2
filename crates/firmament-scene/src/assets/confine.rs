//! Scenes from strangers: every file a scene names must resolve, symbolic links followed, inside
//! one allowed folder, and files are held to tighter [`AssetLimits`]. docs/RELIABILITY.md says
//! how a rendering service uses it.
//!
//! A path is judged before anything is read from it. It is refused when it is absolute, when
//! `..` takes it out of the folder, or when a symbolic link on the way leads out. Links are
//! followed by reading the link itself, never its target, and only while they stay inside the
//! folder, so a refusal never tells whether a file outside exists. What is opened in the end is
//! the resolved path, which has no links left in it.
//!
//! Out of scope: a file system that changes while the scene loads (a link swapped in between the
//! check and the open by someone who can write into the folder at that moment); run the service
//! so that strangers cannot write into the folder while it renders (docs/RELIABILITY.md).

use std::io::ErrorKind;
use std::path::{Component, Path, PathBuf};

use firmament_core::texture::MAX_TEXTURE_SIDE;

use super::limits::{MAX_ASSET_BYTES, MAX_MODEL_INDICES};
use super::paths::lexical_absolute;
use crate::error::SceneError;

/// How large the files of a scene may be: per file, per image and per scene. A scene from a
/// stranger has [`AssetLimits::UNTRUSTED`]; a caller may raise each up to
/// [`AssetLimits::HARD`], the scene format's own limits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct AssetLimits {
    /// The bytes read for one mesh or texture file and every file it names, together.
    pub max_file_bytes: u64,
    /// The longest side of one image, texels.
    pub max_texture_side: u32,
    /// The triangles of the scene's objects together: built-in shapes and mesh files.
    pub max_triangles: u64,
}

impl AssetLimits {
    /// The scene format's hard limits, which apply to every scene: [`MAX_ASSET_BYTES`],
    /// [`MAX_TEXTURE_SIDE`], and 2²⁴ triangles (a model file's own limit; built-in shapes have
    /// the same).
    pub const HARD: Self = Self {
        max_file_bytes: MAX_ASSET_BYTES,
        max_texture_side: MAX_TEXTURE_SIDE,
        max_triangles: (MAX_MODEL_INDICES / 3) as u64,
    };

    /// The defaults for a scene from a stranger: 32 MiB a file, 4096 texels a side, 1 048 576
    /// triangles — a detailed scene of a few models renders within them in seconds.
    pub const UNTRUSTED: Self = Self {
        max_file_bytes: 32 << 20,
        max_texture_side: 4096,
        max_triangles: 1 << 20,
    };

    /// Each limit no higher than its [`HARD`](Self::HARD) one.
    #[must_use]
    pub fn capped(self) -> Self {
        Self {
            max_file_bytes: self.max_file_bytes.min(Self::HARD.max_file_bytes),
            max_texture_side: self.max_texture_side.min(Self::HARD.max_texture_side),
            max_triangles: self.max_triangles.min(Self::HARD.max_triangles),
        }
    }
}

/// The most symbolic links followed for one path (Linux's own limit, `MAXSYMLINKS`).
const MAX_LINKS: usize = 40;

/// One allowed folder and the limits of a scene from a stranger: set it on a
/// [`SceneDocument`](crate::SceneDocument) (or a [`Scene`](crate::Scene)'s `confinement`) and
/// every mesh, texture, flare image and coverage map is judged by [`resolve`](Self::resolve)
/// before it is read, the files a model names (glTF buffers and images, OBJ material
/// libraries and maps) included.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Confinement {
    /// The folder with its links resolved.
    root: PathBuf,
    /// The folder as given, made absolute on its text (a scene's paths may be spelled that way).
    given_root: PathBuf,
    /// What files may hold.
    limits: AssetLimits,
}

/// Why a path is refused, each a rule that quotes nothing but the scene's own text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Refusal {
    /// The path is absolute.
    Absolute,
    /// `..` takes it out of the folder (or it names a place outside it).
    Outside,
    /// A symbolic link on the way leads out of the folder.
    LinkOut,
    /// Too many links on the way.
    TooManyLinks,
    /// Nothing by that name in the folder.
    Missing,
    /// The operating system would not say (permission, a file used as a folder).
    Unreadable(ErrorKind),
}

impl Refusal {
    /// The rule broken, for messages.
    pub(crate) fn rule(self) -> String {
        match self {
            Self::Absolute => "untrusted mode refuses absolute paths: name a file inside the allowed folder by a \
                               path relative to the scene's folder"
                .to_owned(),
            Self::Outside => "climbs out of the allowed folder (untrusted mode reads only files inside it)".to_owned(),
            Self::LinkOut => "a symbolic link on the way leads out of the allowed folder (untrusted mode reads \
                              only files inside it)"
                .to_owned(),
            Self::TooManyLinks => format!("more than {MAX_LINKS} symbolic links on the way (a loop?)"),
            Self::Missing => "no such file in the allowed folder".to_owned(),
            Self::Unreadable(kind) => format!("cannot be looked up in the allowed folder ({kind})"),
        }
    }
}

impl Confinement {
    /// Files only from `root` (and the folders inside it), with [`AssetLimits::UNTRUSTED`].
    ///
    /// # Errors
    /// [`SceneError::Read`] when `root` is not a folder that can be looked up.
    pub fn new(root: &Path) -> Result<Self, SceneError> {
        let unreadable = |reason: String| SceneError::Read {
            path: root.display().to_string(),
            reason,
        };
        let resolved = std::fs::canonicalize(root).map_err(|e| unreadable(format!("the allowed folder: {e}")))?;
        if !resolved.is_dir() {
            return Err(unreadable("the allowed folder is not a folder".to_owned()));
        }
        Ok(Self {
            root: resolved,
            given_root: lexical_absolute(root),
            limits: AssetLimits::UNTRUSTED,
        })
    }

    /// The same folder with `limits`, each capped at [`AssetLimits::HARD`].
    #[must_use]
    pub fn with_limits(self, limits: AssetLimits) -> Self {
        Self {
            limits: limits.capped(),
            ..self
        }
    }

    /// The limits files are held to.
    pub fn limits(&self) -> AssetLimits {
        self.limits
    }

    /// The allowed folder, links resolved.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The file that scene key `key`, written `written` in a scene whose folder is `base_dir`,
    /// names: its path inside the allowed folder with every link resolved, ready to open.
    ///
    /// # Errors
    /// [`SceneError::Invalid`] naming `key`, the path as written and the rule: a path out of
    /// the folder (by `..` or a link), or no such file; an absolute path is
    /// [`SceneError::WrongType`], naming the key and the rule without quoting the path.
    pub fn resolve(&self, key: &str, base_dir: &Path, written: &Path) -> Result<PathBuf, SceneError> {
        if written.is_absolute() || written.has_root() {
            // Not quoted: the message names no place outside the folder, even one the scene gave.
            return Err(SceneError::WrongType {
                key: key.to_owned(),
                message: Refusal::Absolute.rule(),
            });
        }
        let refused =
            |why: Refusal| SceneError::invalid(key, format!("{:?}", written.display().to_string()), why.rule());
        self.resolve_path(&base_dir.join(written)).map_err(refused)
    }

    /// `path` (absolute, or relative to the working directory) resolved inside the folder.
    pub(crate) fn resolve_path(&self, path: &Path) -> Result<PathBuf, Refusal> {
        let lexical = lexical_absolute(path);
        let inside = self.inside(&lexical).ok_or(Refusal::Outside)?;
        self.walk(&inside)
    }

    /// `path` (absolute, `.` and `..` already taken out) relative to the folder, when it lies in
    /// it by either spelling of the folder.
    fn inside(&self, path: &Path) -> Option<PathBuf> {
        let relative = path
            .strip_prefix(&self.root)
            .or_else(|_| path.strip_prefix(&self.given_root))
            .ok()?;
        relative
            .components()
            .all(|c| matches!(c, Component::Normal(_)))
            .then(|| relative.to_path_buf())
    }

    /// Follows `relative` from the folder one name at a time, reading each link met (never its
    /// target) and going on from where it points while that stays inside.
    fn walk(&self, relative: &Path) -> Result<PathBuf, Refusal> {
        let mut resolved = self.root.clone();
        // The names still to follow, the next one last.
        let mut pending: Vec<std::ffi::OsString> = relative.iter().rev().map(ToOwned::to_owned).collect();
        let mut links = 0;
        while let Some(name) = pending.pop() {
            let next = resolved.join(&name);
            let looked_up = |e: std::io::Error| match e.kind() {
                ErrorKind::NotFound => Refusal::Missing,
                kind => Refusal::Unreadable(kind),
            };
            let meta = std::fs::symlink_metadata(&next).map_err(looked_up)?;
            if !meta.file_type().is_symlink() {
                resolved = next;
                continue;
            }
            links += 1;
            if links > MAX_LINKS {
                return Err(Refusal::TooManyLinks);
            }
            let target = std::fs::read_link(&next).map_err(looked_up)?;
            // `resolved` has no links, so `..` in a relative target is taken on the text.
            let target = lexical_absolute(&resolved.join(target));
            let rest = self.inside(&target).ok_or(Refusal::LinkOut)?;
            resolved.clone_from(&self.root);
            pending.extend(rest.iter().rev().map(ToOwned::to_owned));
        }
        Ok(resolved)
    }
}

#[cfg(all(test, unix))]
mod tests {
    use std::os::unix::fs::symlink;

    use super::*;

    /// A folder `root` holding `a.png` and `sub/b.png`, beside `secret.txt` outside it.
    fn folders() -> (tempfile::TempDir, PathBuf) {
        let top = tempfile::tempdir().expect("a temporary folder");
        let root = top.path().join("root");
        std::fs::create_dir_all(root.join("sub")).expect("folders");
        for file in [
            root.join("a.png"),
            root.join("sub/b.png"),
            top.path().join("secret.txt"),
        ] {
            std::fs::write(file, b"x").expect("a file");
        }
        (top, root)
    }

    fn resolve(confinement: &Confinement, root: &Path, written: &str) -> Result<PathBuf, Refusal> {
        confinement.resolve_path(&root.join(written))
    }

    #[test]
    fn files_inside_resolve_to_their_real_paths() {
        let (_top, root) = folders();
        let c = Confinement::new(&root).expect("a folder");
        let real = std::fs::canonicalize(&root).expect("resolves");
        assert_eq!(resolve(&c, &root, "a.png"), Ok(real.join("a.png")));
        assert_eq!(resolve(&c, &root, "sub/../sub/./b.png"), Ok(real.join("sub/b.png")));
        symlink("sub/b.png", root.join("link.png")).expect("a link");
        symlink("../a.png", root.join("sub/up.png")).expect("a link");
        symlink(real.join("sub"), root.join("folder")).expect("a link");
        assert_eq!(resolve(&c, &root, "link.png"), Ok(real.join("sub/b.png")));
        assert_eq!(resolve(&c, &root, "sub/up.png"), Ok(real.join("a.png")));
        assert_eq!(resolve(&c, &root, "folder/up.png"), Ok(real.join("a.png")));
        assert_eq!(resolve(&c, &root, "nothing.png"), Err(Refusal::Missing));
    }

    #[test]
    fn paths_out_of_the_folder_are_refused_whether_or_not_the_file_exists() {
        let (top, root) = folders();
        let c = Confinement::new(&root).expect("a folder");
        for written in ["../secret.txt", "../nothing.txt", "sub/../../secret.txt"] {
            assert_eq!(resolve(&c, &root, written), Err(Refusal::Outside), "{written}");
        }
        symlink(top.path().join("secret.txt"), root.join("out.png")).expect("a link");
        symlink("../nothing.txt", root.join("dangling.png")).expect("a link");
        symlink(top.path(), root.join("up")).expect("a link");
        for written in ["out.png", "dangling.png", "up/secret.txt", "up/root/a.png"] {
            assert_eq!(resolve(&c, &root, written), Err(Refusal::LinkOut), "{written}");
        }
        symlink("loop2", root.join("loop1")).expect("a link");
        symlink("loop1", root.join("loop2")).expect("a link");
        assert_eq!(resolve(&c, &root, "loop1"), Err(Refusal::TooManyLinks));
    }

    #[test]
    fn scene_keys_are_refused_by_name_and_rule() {
        let (top, root) = folders();
        let c = Confinement::new(&root).expect("a folder");
        let secret = top.path().join("secret.txt");
        let message = c
            .resolve("objects[0].texture.file", &root, &secret)
            .expect_err("absolute")
            .to_string();
        assert!(
            message.starts_with("objects[0].texture.file: untrusted mode refuses absolute paths"),
            "{message}"
        );
        let message = c
            .resolve("clouds[1].coverage_map", &root, Path::new("../secret.txt"))
            .expect_err("out")
            .to_string();
        assert!(
            message.contains("clouds[1].coverage_map = \"../secret.txt\": climbs out of the allowed folder"),
            "{message}"
        );
        assert!(!message.contains(&*top.path().to_string_lossy()), "{message}");
    }

    #[test]
    fn the_folder_may_be_named_through_a_link_and_limits_are_capped() {
        let (top, root) = folders();
        let alias = top.path().join("alias");
        symlink(&root, &alias).expect("a link");
        let c = Confinement::new(&alias).expect("a folder");
        assert!(resolve(&c, &alias, "a.png").is_ok());
        assert!(resolve(&c, &root, "a.png").is_ok());
        let huge = AssetLimits {
            max_file_bytes: u64::MAX,
            max_texture_side: u32::MAX,
            max_triangles: u64::MAX,
        };
        assert_eq!(c.with_limits(huge).limits(), AssetLimits::HARD);
        assert!(Confinement::new(&root.join("a.png")).is_err());
    }
}
