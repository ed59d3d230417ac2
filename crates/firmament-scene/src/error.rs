//! The scene crate's one error type. Every message names the key path, the value and the rule.

/// Why a scene could not be built. More variants may come, hence `#[non_exhaustive]`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The scene file could not be read.
    #[error("cannot read scene file {path}: {reason}")]
    Read {
        /// The path given.
        path: String,
        /// What the operating system said.
        reason: String,
    },
    /// The text is not valid TOML.
    #[error("{origin} is not valid TOML: {message}")]
    Syntax {
        /// Where the text came from.
        origin: String,
        /// The parser's message, with line and column.
        message: String,
    },
    /// No built-in preset has this name.
    #[error("unknown preset `{name}`{suggestion}; presets are: {known}")]
    UnknownPreset {
        /// The name given.
        name: String,
        /// `; did you mean ...?` or empty.
        suggestion: String,
        /// Every preset's name, comma-separated.
        known: String,
    },
    /// Presets name each other in a loop, or too deeply.
    #[error("preset `{name}` builds on presets more than {depth} deep (a loop?)")]
    PresetTooDeep {
        /// The preset where it stopped.
        name: String,
        /// The depth limit.
        depth: usize,
    },
    /// A key that the format does not have.
    #[error("{key}: unknown key{suggestion}")]
    UnknownKey {
        /// The full key path.
        key: String,
        /// ` (did you mean `x`?)` or empty.
        suggestion: String,
    },
    /// A value of the wrong type or form.
    #[error("{key}: {message}")]
    WrongType {
        /// The full key path.
        key: String,
        /// What was expected and found.
        message: String,
    },
    /// A value that breaks its rule.
    #[error("{key} = {value}: {rule}")]
    Invalid {
        /// The full key path.
        key: String,
        /// The value as given.
        value: String,
        /// The rule it broke.
        rule: String,
    },
    /// A mesh or texture file named by the scene could not be loaded.
    #[error("{key}: cannot load {path}: {reason}")]
    Asset {
        /// The key that named the file (`objects[2].mesh.file`).
        key: String,
        /// The path as resolved (relative paths are taken from the scene file's folder).
        path: String,
        /// What is wrong: the OS error, or the first broken rule of the format.
        reason: String,
    },
    /// A scene file could not be written (nothing was written: saves are atomic).
    #[error("cannot write scene file {path}: {reason}")]
    Write {
        /// The path given.
        path: String,
        /// What went wrong: the operating system's message, or what the scene cannot express.
        reason: String,
    },
    /// A `key.path=value` override that cannot be applied.
    #[error("--set {item}: {rule}")]
    BadOverride {
        /// The override as given.
        item: String,
        /// What is wrong with it.
        rule: String,
    },
}

impl SceneError {
    /// An [`SceneError::Invalid`] for `key = value`.
    pub(crate) fn invalid(key: impl Into<String>, value: impl std::fmt::Display, rule: impl Into<String>) -> Self {
        Self::Invalid {
            key: key.into(),
            value: value.to_string(),
            rule: rule.into(),
        }
    }
}

/// ` (did you mean `x`?)` for the closest candidate, or empty when none is close.
pub(crate) fn did_you_mean<'a>(given: &str, candidates: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(given, c), c))
        .filter(|(score, _)| *score > 0.7)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}
