//! Every fuzz target, on stable and without libFuzzer: over its seed corpus (`seeds/<target>/`,
//! and the presets for the scene targets), its past crash inputs (`regressions/<target>/`) and a
//! fixed number of deterministic mutations of them (byte flips, interesting bytes and numbers,
//! insertions, deletions, truncations, splices; `rand_pcg` with a fixed seed). A panic anywhere
//! fails, even one that a loader catches and turns into an error. A failing input is written to
//! `$CARGO_TARGET_TMPDIR/fuzz-smoke/` for `fuzz/` or a regression file.
//!
//! `FIRMAMENT_FUZZ_SMOKE_SCALE=N` runs N times as many mutations (a longer run by hand).
//! `FIRMAMENT_FUZZ_SMOKE_SECONDS=N` instead mutates each target for N seconds (CI runs 30 s a
//! target: `.ci/run`): the same seeded sequence of inputs, only as far into it as the time allows;
//! each target prints how many mutations it ran (`-- --nocapture` shows it).

use std::cell::RefCell;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Once;
use std::time::{Duration, Instant};

use firmament_fuzz::{TARGETS, Target, target};
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;

thread_local! {
    /// The first panic on this thread since it was last taken (caught or not).
    static PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Records every panic in [`PANIC`] before the default hook prints it.
fn install_panic_hook() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            PANIC.with(|p| {
                p.borrow_mut().get_or_insert_with(|| info.to_string());
            });
            previous(info);
        }));
    });
}

/// Bytes and numbers that break parsers: limits, special floats, brackets, quotes, separators.
const TOKENS: &[&str] = &[
    "0",
    "-1",
    "-0",
    "1e309",
    "-1e309",
    "nan",
    "inf",
    "-inf",
    "1e-320",
    "255",
    "256",
    "65535",
    "65536",
    "2147483647",
    "2147483648",
    "-2147483649",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "99999999999999999999999",
    "[",
    "]",
    "{",
    "}",
    "\"",
    "'",
    ",",
    "=",
    ":",
    ".",
    "/",
    "\\",
    "\n",
    "#",
    "%",
    "-",
    "+",
    "T",
    "Z",
    "e",
    "[[",
    "]]",
    "\u{0}",
    "\u{ff}",
    "é",
    "data:",
    "file:///",
    "../",
];

/// One random change to `input`; `corpus` gives the other half of splices.
fn mutate(rng: &mut Pcg64, input: &mut Vec<u8>, corpus: &[Vec<u8>]) {
    let at = |rng: &mut Pcg64, len: usize| rng.random_range(0..=len);
    match rng.random_range(0..9) {
        0 if !input.is_empty() => {
            let i = rng.random_range(0..input.len());
            input[i] ^= 1 << rng.random_range(0..8);
        }
        1 if !input.is_empty() => {
            let i = rng.random_range(0..input.len());
            input[i] = [0, 0xff, 0x7f, 0x80, b'0', b'9', b'-', b'.', b' '][rng.random_range(0..9)];
        }
        2 if !input.is_empty() => {
            let start = rng.random_range(0..input.len());
            let end = (start + rng.random_range(1..=16)).min(input.len());
            input.drain(start..end);
        }
        3 => {
            let i = at(rng, input.len());
            let n = rng.random_range(1..=8);
            let bytes: Vec<u8> = (0..n).map(|_| rng.random()).collect();
            input.splice(i..i, bytes);
        }
        4 => {
            let cut = at(rng, input.len());
            input.truncate(cut);
        }
        5 if !corpus.is_empty() => {
            let other = &corpus[rng.random_range(0..corpus.len())];
            let cut = at(rng, input.len());
            let from = at(rng, other.len());
            input.truncate(cut);
            input.extend_from_slice(&other[from..]);
        }
        6 if !input.is_empty() => {
            // Copy a chunk of the input somewhere else in it.
            let start = rng.random_range(0..input.len());
            let end = (start + rng.random_range(1..=64)).min(input.len());
            let chunk = input[start..end].to_vec();
            let i = at(rng, input.len());
            input.splice(i..i, chunk);
        }
        7 => {
            let token = TOKENS[rng.random_range(0..TOKENS.len())].as_bytes();
            let i = at(rng, input.len());
            input.splice(i..i, token.iter().copied());
        }
        _ => {
            // Replace a run of digits with an interesting number.
            let digits: Vec<usize> = (0..input.len()).filter(|&i| input[i].is_ascii_digit()).collect();
            if digits.is_empty() {
                return;
            }
            let start = digits[rng.random_range(0..digits.len())];
            let end = (start..input.len())
                .find(|&i| !input[i].is_ascii_digit())
                .unwrap_or(input.len());
            let token = TOKENS[rng.random_range(0..21)].as_bytes();
            input.splice(start..end, token.iter().copied());
        }
    }
}

/// Every file of `folder`, sorted by name (none when it does not exist).
fn files(folder: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let Ok(entries) = std::fs::read_dir(folder) else {
        return Vec::new();
    };
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file())
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).expect("reads a corpus file");
            (p, bytes)
        })
        .collect()
}

/// The seeds of `target`: its folder, and the presets for the scene targets.
fn seeds(target: &Target) -> Vec<Vec<u8>> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut seeds: Vec<Vec<u8>> = files(&dir.join("seeds").join(target.name))
        .into_iter()
        .map(|(_, b)| b)
        .collect();
    match target.name {
        "scene_toml" => seeds.extend(firmament_scene::PRESETS.iter().map(|p| p.toml.as_bytes().to_vec())),
        "scene_set" => seeds.extend(firmament_scene::PRESETS.iter().map(|p| p.name.as_bytes().to_vec())),
        _ => {}
    }
    seeds
}

/// Runs `target` on `input`; on a panic (caught by a loader or not) writes the input out and
/// fails naming it.
fn run_one(target: &Target, input: &[u8], what: &str) {
    PANIC.with(|p| p.borrow_mut().take());
    let result = catch_unwind(AssertUnwindSafe(|| (target.run)(input)));
    let panic = PANIC.with(|p| p.borrow_mut().take());
    if result.is_ok() && panic.is_none() {
        return;
    }
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz-smoke");
    std::fs::create_dir_all(&dir).expect("creates the failure folder");
    let file = dir.join(format!("{}-{}", target.name, what.replace(['/', ' '], "_")));
    std::fs::write(&file, input).expect("writes the failing input");
    panic!(
        "fuzz target {} panicked on {what} (input written to {}; run it with \
         `cargo +nightly fuzz run {} {}`): {}",
        target.name,
        file.display(),
        target.name,
        file.display(),
        panic.unwrap_or_default()
    );
}

/// How long the mutations of one smoke run go on.
#[derive(Debug, Clone, Copy)]
enum Budget {
    /// This many mutated inputs.
    Count(usize),
    /// As many as fit in this time.
    Time(Duration),
}

impl Budget {
    /// `FIRMAMENT_FUZZ_SMOKE_SECONDS` when set, else `mutations` times
    /// `FIRMAMENT_FUZZ_SMOKE_SCALE` (1 when unset).
    fn from_env(mutations: usize) -> Self {
        let var = |name: &str| {
            std::env::var(name).ok().map(|text| {
                text.trim()
                    .parse::<u64>()
                    .unwrap_or_else(|_| panic!("{name}={text:?}: must be a whole number"))
            })
        };
        match (var("FIRMAMENT_FUZZ_SMOKE_SECONDS"), var("FIRMAMENT_FUZZ_SMOKE_SCALE")) {
            (Some(seconds), _) => Self::Time(Duration::from_secs(seconds)),
            (None, scale) => Self::Count(mutations.saturating_mul(scale.unwrap_or(1) as usize)),
        }
    }

    /// Whether mutation number `done` (0-based) is still within the budget, `since` the first.
    fn allows(self, done: usize, since: Instant) -> bool {
        match self {
            Self::Count(n) => done < n,
            Self::Time(t) => since.elapsed() < t,
        }
    }
}

/// The smoke run of one target: every corpus input, then `mutations` mutated ones (or as many
/// as `FIRMAMENT_FUZZ_SMOKE_SECONDS` allows, see [`Budget`]).
fn smoke(name: &str, mutations: usize) {
    install_panic_hook();
    let target = target(name).expect("a target of that name");
    let budget = Budget::from_env(mutations);
    let started = Instant::now();
    let regressions = files(&Path::new(env!("CARGO_MANIFEST_DIR")).join("regressions").join(name));
    for (path, input) in &regressions {
        let shown = path
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        run_one(target, input, &format!("regression {shown}"));
    }
    let mut corpus = seeds(target);
    let seed_count = corpus.len();
    assert!(!corpus.is_empty(), "{name} has no seeds");
    for (i, input) in corpus.iter().enumerate() {
        run_one(target, input, &format!("seed {i}"));
    }
    let regression_count = regressions.len();
    corpus.extend(regressions.into_iter().map(|(_, b)| b));
    // A fixed seed per target: the same inputs every run.
    let mut rng = Pcg64::seed_from_u64(
        name.bytes()
            .fold(0xcafe_f00d_u64, |h, b| h.rotate_left(5) ^ u64::from(b)),
    );
    let mutating = Instant::now();
    let mut done = 0;
    while budget.allows(done, mutating) {
        let i = done;
        done += 1;
        let mut input = corpus[rng.random_range(0..corpus.len())].clone();
        for _ in 0..rng.random_range(1..=4) {
            mutate(&mut rng, &mut input, &corpus);
        }
        run_one(target, &input, &format!("mutation {i}"));
    }
    eprintln!(
        "{name}: {} regressions, {} seeds, {done} mutations in {:.2?} ({})",
        regression_count,
        seed_count,
        started.elapsed(),
        match budget {
            Budget::Count(_) => "a fixed count".to_owned(),
            Budget::Time(t) => format!("a budget of {} s", t.as_secs()),
        }
    );
}

#[test]
fn every_target_is_smoke_tested() {
    let tested = ["scene_toml", "scene_set", "obj", "gltf", "glb", "texture", "date_time"];
    for t in TARGETS {
        assert!(tested.contains(&t.name), "{} has no smoke test below", t.name);
    }
}

#[test]
fn scene_toml() {
    smoke("scene_toml", 3000);
}

#[test]
fn scene_set() {
    smoke("scene_set", 3000);
}

#[test]
fn obj() {
    smoke("obj", 10000);
}

#[test]
fn gltf() {
    smoke("gltf", 10000);
}

#[test]
fn glb() {
    smoke("glb", 10000);
}

#[test]
fn texture() {
    smoke("texture", 6000);
}

#[test]
fn date_time() {
    smoke("date_time", 20000);
}

/// The seeds reach the loaders' success paths, where most of the code is.
#[test]
fn model_texture_and_date_seeds_load() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("seeds");
    for (folder, extension) in [("obj", "obj"), ("gltf", "gltf"), ("glb", "glb")] {
        for (path, bytes) in files(&dir.join(folder)) {
            let bytes = if folder == "glb" {
                firmament_fuzz::glb_container(&bytes)
            } else {
                bytes
            };
            let name = Path::new("/nonexistent-firmament-fuzz/model").with_extension(extension);
            let meshes = firmament_scene::assets::load_model_bytes("seed", &name, &bytes)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(!meshes.is_empty());
        }
    }
    for (path, bytes) in files(&dir.join("texture")) {
        firmament_scene::assets::load_texture_bytes("seed", Path::new("t.png"), &bytes)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    for (path, bytes) in files(&dir.join("date_time")) {
        let text = std::str::from_utf8(&bytes[8..]).expect("UTF-8");
        firmament_scene::parse_date_time(text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
    for (path, bytes) in files(&dir.join("scene_set")) {
        let text = std::str::from_utf8(&bytes).expect("UTF-8");
        let mut lines = text.lines();
        let preset = lines.next().expect("a preset");
        let overrides: Vec<String> = lines.map(str::to_owned).collect();
        firmament_scene::load(firmament_scene::SceneSource::Preset(preset), None, &overrides)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}
