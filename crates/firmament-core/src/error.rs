//! The core's one error type.

/// What can go wrong when building core models from user data.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CoreError {
    /// A day cycle needs at least one keyframe.
    #[error("a day cycle needs at least one keyframe")]
    NoKeyframes,
    /// Two keyframes share a time of day.
    #[error("keyframes {first} and {second} are both at {time}: each keyframe needs its own time")]
    DuplicateKeyframeTime {
        /// Index of the first keyframe, as given.
        first: usize,
        /// Index of the second keyframe, as given.
        second: usize,
        /// The shared time, `HH:MM:SS`.
        time: String,
    },
    /// A value broke its rule.
    #[error("{field} = {value}: {rule}")]
    Invalid {
        /// The field's name.
        field: &'static str,
        /// The value as given.
        value: String,
        /// The rule it broke.
        rule: &'static str,
    },
    /// A value of an indexed item (`flare.elements[3].size`) broke its rule.
    #[error("{field} = {value}: {rule}")]
    InvalidItem {
        /// The field's full name, with the item's index.
        field: String,
        /// The value as given.
        value: String,
        /// The rule it broke.
        rule: &'static str,
    },
}
