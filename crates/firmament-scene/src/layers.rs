//! Layering TOML tables: parsing, merging one over another, and `key.path=value` overrides
//! (`presets.rs` layers presets under files with these).

use crate::error::SceneError;

/// The most parts a key path may have (`suns.0.elevation` has 3): the nesting limit the `toml`
/// crate sets for scene files, so that an override cannot build a table nested deeper than a file
/// can (a path of thousands of parts would overflow the stack when the table is walked or dropped).
pub(crate) const MAX_KEY_PARTS: usize = 80;

/// Parses TOML text into a table, naming `origin` in the error.
pub(crate) fn parse_table(text: &str, origin: &str) -> Result<toml::Table, SceneError> {
    text.parse::<toml::Table>().map_err(|e| SceneError::Syntax {
        origin: origin.to_owned(),
        message: e.to_string().trim_end().to_owned(),
    })
}

/// Merges `top` into `base`: tables merge key by key, anything else replaces.
pub(crate) fn merge(base: &mut toml::Table, top: toml::Table) {
    for (key, value) in top {
        match (base.get_mut(&key), value) {
            (Some(toml::Value::Table(below)), toml::Value::Table(above)) => merge(below, above),
            (_, value) => {
                base.insert(key, value);
            }
        }
    }
}

/// Applies one `key.path=value` override. The value is read as TOML (`3`, `true`, `[1, 2, 3]`,
/// `"text"`); anything that is not valid TOML is taken as a bare string (`tone_curve=aces_fitted`).
/// Array elements are addressed by index: `sky.gradient.keyframes.0.zenith=#ff0000`; the index one
/// past the end appends a new table to set keys in (`suns.1.azimuth=90` on a list of one sun).
pub(crate) fn apply_override(table: &mut toml::Table, item: &str) -> Result<(), SceneError> {
    let bad = |rule: &str| SceneError::BadOverride {
        item: item.to_owned(),
        rule: rule.to_owned(),
    };
    let (path, raw) = item.split_once('=').ok_or_else(|| bad("expected key.path=value"))?;
    set_path(table, path.trim(), parse_value(raw.trim())).map_err(|rule| bad(&rule))
}

/// Sets the value at a dotted key path (`suns.0.elevation`), addressed as [`apply_override`]
/// does; the error is the rule the path breaks.
pub(crate) fn set_path(table: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), String> {
    let keys: Vec<&str> = path.split('.').collect();
    if keys.iter().any(|k| k.is_empty()) {
        return Err("the key path has an empty part".to_owned());
    }
    if keys.len() > MAX_KEY_PARTS {
        return Err(format!(
            "the key path has {} parts, more than the {MAX_KEY_PARTS} a scene's tables may nest (a hard limit of the \
             scene format, as of TOML files)",
            keys.len()
        ));
    }
    let mut root = toml::Value::Table(std::mem::take(table));
    let result = assign(&mut root, &keys, value);
    if let toml::Value::Table(t) = root {
        *table = t;
    }
    result
}

fn parse_value(raw: &str) -> toml::Value {
    // Wrap in a one-key document so TOML's own parser decides what the value is.
    format!("v = {raw}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(raw.to_owned()))
}

/// Sets `keys` under `node` to `value`, creating missing tables; numeric keys index arrays (one
/// past the end appends a table when there are keys left to set in it).
fn assign(node: &mut toml::Value, keys: &[&str], value: toml::Value) -> Result<(), String> {
    let Some((key, rest)) = keys.split_first() else {
        *node = value;
        return Ok(());
    };
    let child = match node {
        toml::Value::Table(t) => t
            .entry((*key).to_owned())
            .or_insert_with(|| toml::Value::Table(toml::Table::new())),
        toml::Value::Array(items) => {
            let len = items.len();
            let index: usize = key
                .parse()
                .map_err(|_| format!("`{key}` must be an array index (0 to {len})"))?;
            if index == len && !rest.is_empty() {
                // One past the end, with keys to set inside: append a new table for them.
                items.push(toml::Value::Table(toml::Table::new()));
            }
            items.get_mut(index).ok_or_else(|| {
                format!("index {index} is past the end of an array of {len} (index {len} appends a table)")
            })?
        }
        other => return Err(format!("cannot set `{key}` inside a {}", other.type_str())),
    };
    assign(child, rest, value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deep_key_paths_are_refused_before_they_are_built() {
        let mut table = toml::Table::new();
        let deep = vec!["a"; 100_000].join(".");
        let error = apply_override(&mut table, &format!("{deep}=1")).expect_err("too deep");
        assert!(error.to_string().contains("100000 parts, more than the 80"), "{error}");
        assert!(table.is_empty());
        let deepest = vec!["a"; MAX_KEY_PARTS].join(".");
        apply_override(&mut table, &format!("{deepest}=1")).expect("80 parts");
    }
}
