//! The `#import` preprocessor: WGSL has no includes, so each module names the modules it uses on
//! lines `#import common/ellipsoid` at its top (after its header comment, before any code), and
//! [`compose_with`] puts them together: imports depth-first, each module once, every import
//! before its importer, the directive lines taken out so that naga and wgpu see plain WGSL.
//!
//! A module's name is its path under `src/shaders/` without `.wgsl`. Written here rather than
//! taken from naga_oil (which does not follow naga 30, wgpu 30's) because this is all firmament
//! needs: no conditionals, no renaming, every module in one namespace.

use std::borrow::Cow;
use std::collections::HashSet;

/// The directive keyword.
const IMPORT: &str = "#import";

/// Why a module could not be composed. Files are named as `atmosphere/sky.wgsl`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ComposeError {
    /// The module asked for does not exist.
    #[error("no WGSL module `{0}`")]
    NoSuchModule(String),
    /// A module imports one that does not exist.
    #[error("{file}: `#import {import}`: no such module")]
    UnknownImport {
        /// The importing file.
        file: String,
        /// The module it names.
        import: String,
    },
    /// A module imports one that (through others) imports it.
    #[error("{file}: `#import {import}` closes an import cycle: {}", cycle.join(" → "))]
    Cycle {
        /// The importing file.
        file: String,
        /// The module it names.
        import: String,
        /// The modules around the cycle, from `import` back to it.
        cycle: Vec<String>,
    },
    /// A malformed or misplaced directive.
    #[error("{file}, line {line}: {problem}")]
    Directive {
        /// The file.
        file: String,
        /// Its 1-based line.
        line: usize,
        /// What is wrong.
        problem: String,
    },
}

/// The file a module is read from, for messages.
fn file_name(module: &str) -> String {
    format!("{module}.wgsl")
}

/// A module split into the modules it imports (in order) and its WGSL without the directive
/// lines.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Module<'a> {
    /// The imported modules' names.
    pub(crate) imports: Vec<&'a str>,
    /// The WGSL, each remaining line ending in `\n`.
    pub(crate) body: String,
}

/// Splits module `name`'s `source`. Directives are lines starting with `#`; the only one is
/// `#import <module>`, allowed only before the first line of code (blank and `//` lines are not
/// code).
pub(crate) fn parse<'a>(name: &str, source: &'a str) -> Result<Module<'a>, ComposeError> {
    let mut imports = Vec::new();
    let mut body = String::with_capacity(source.len());
    let mut code_seen = false;
    for (index, line) in source.lines().enumerate() {
        let trimmed = line.trim();
        let problem = |problem: &str| ComposeError::Directive {
            file: file_name(name),
            line: index + 1,
            problem: problem.to_owned(),
        };
        if !trimmed.starts_with('#') {
            code_seen |= !(trimmed.is_empty() || trimmed.starts_with("//"));
            body.push_str(line);
            body.push('\n');
            continue;
        }
        let mut words = trimmed.split_whitespace();
        if words.next() != Some(IMPORT) {
            return Err(problem(&format!("unknown directive `{trimmed}` (only `{IMPORT}`)")));
        }
        let (Some(import), None) = (words.next(), words.next()) else {
            return Err(problem(&format!("`{IMPORT}` takes one module name: `{trimmed}`")));
        };
        if code_seen {
            return Err(problem(&format!(
                "`{trimmed}` after WGSL code: imports go at the top, after the header"
            )));
        }
        imports.push(import);
    }
    Ok(Module { imports, body })
}

/// Module `entry` with every module it imports, directly or not, before it: imports depth-first
/// in the order written, each module once. `lookup` gives a module's source by name.
pub(crate) fn compose_with<'s>(
    entry: &str,
    lookup: impl Fn(&str) -> Option<Cow<'s, str>>,
) -> Result<String, ComposeError> {
    let source = lookup(entry).ok_or_else(|| ComposeError::NoSuchModule(entry.to_owned()))?;
    let mut composer = Composer {
        lookup: &lookup,
        stack: Vec::new(),
        done: HashSet::new(),
        parts: Vec::new(),
    };
    composer.visit(entry, &source)?;
    // One blank line between modules, as when they were concatenated by hand.
    Ok(composer.parts.join("\n"))
}

/// The state of one composition.
struct Composer<'l, L> {
    lookup: &'l L,
    /// The modules being visited, outermost first (to find cycles).
    stack: Vec<String>,
    /// The modules already written.
    done: HashSet<String>,
    /// The bodies written, in order.
    parts: Vec<String>,
}

impl<'s, L: Fn(&str) -> Option<Cow<'s, str>>> Composer<'_, L> {
    fn visit(&mut self, name: &str, source: &str) -> Result<(), ComposeError> {
        let module = parse(name, source)?;
        self.stack.push(name.to_owned());
        for import in module.imports {
            if self.done.contains(import) {
                continue;
            }
            if let Some(start) = self.stack.iter().position(|m| m == import) {
                let mut cycle = self.stack[start..].to_vec();
                cycle.push(import.to_owned());
                return Err(ComposeError::Cycle {
                    file: file_name(name),
                    import: import.to_owned(),
                    cycle,
                });
            }
            let source = (self.lookup)(import).ok_or_else(|| ComposeError::UnknownImport {
                file: file_name(name),
                import: import.to_owned(),
            })?;
            self.visit(import, &source)?;
        }
        self.stack.pop();
        self.done.insert(name.to_owned());
        self.parts.push(module.body);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composes `entry` from an in-memory table.
    fn compose(entry: &str, table: &[(&str, &'static str)]) -> Result<String, ComposeError> {
        compose_with(entry, |name| {
            table
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, source)| Cow::Borrowed(*source))
        })
    }

    #[test]
    fn imports_come_first_once_each_without_their_directives() {
        let table = [
            ("a", "// a\n#import b\n#import c\nfn a() {}\n"),
            ("b", "#import d\nfn b() {}\n"),
            ("c", "// c\n\n#import d\n#import b\nfn c() {}\n"),
            ("d", "fn d() {}\n"),
        ];
        assert_eq!(
            compose("a", &table).unwrap(),
            "fn d() {}\n\nfn b() {}\n\n// c\n\nfn c() {}\n\n// a\nfn a() {}\n"
        );
    }

    #[test]
    fn a_module_without_imports_is_its_own_text() {
        let text = "// x.wgsl\nconst X: u32 = 1u;\n";
        assert_eq!(compose("x", &[("x", text)]).unwrap(), text);
    }

    #[test]
    fn cycles_are_errors_naming_the_file_and_the_import() {
        let table = [
            ("a", "#import b\n"),
            ("b", "#import c\n"),
            ("c", "#import a\n"),
            ("self", "#import self\n"),
        ];
        let error = compose("a", &table).unwrap_err();
        assert_eq!(
            error,
            ComposeError::Cycle {
                file: "c.wgsl".into(),
                import: "a".into(),
                cycle: vec!["a".into(), "b".into(), "c".into(), "a".into()],
            }
        );
        assert_eq!(
            error.to_string(),
            "c.wgsl: `#import a` closes an import cycle: a → b → c → a"
        );
        assert!(matches!(
            compose("self", &table),
            Err(ComposeError::Cycle { import, .. }) if import == "self"
        ));
    }

    #[test]
    fn unknown_modules_are_errors_naming_the_file_and_the_import() {
        let table = [("a", "#import b\n"), ("b", "// b\n#import common/nowhere\n")];
        let error = compose("a", &table).unwrap_err();
        assert_eq!(error.to_string(), "b.wgsl: `#import common/nowhere`: no such module");
        assert_eq!(compose("z", &table), Err(ComposeError::NoSuchModule("z".into())));
    }

    #[test]
    fn malformed_and_late_directives_are_errors() {
        for (source, line) in [
            ("fn a() {}\n#import b\n", 2),
            ("#include b\n", 1),
            ("// x\n#import\n", 2),
            ("#import b c\n", 1),
        ] {
            match compose("a", &[("a", source), ("b", "")]) {
                Err(ComposeError::Directive { file, line: l, .. }) => {
                    assert_eq!((file.as_str(), l), ("a.wgsl", line), "{source:?}");
                }
                other => panic!("{source:?}: {other:?}"),
            }
        }
    }
}
