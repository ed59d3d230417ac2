//! The integration tests of `firmament-scene`, in one test binary (one link instead of one per
//! file): one module per subject. Run one with `cargo test -p firmament-scene --test scene
//! <module>::`, e.g. `flare_scenes::`.

mod assets;
mod atmosphere_scenes;
mod body_scenes;
mod builder;
mod cloud_scenes;
mod document;
mod empirical_scenes;
mod flare_scenes;
mod medium_terms_scenes;
mod object_scenes;
mod scene_files;
mod shadow_scenes;
mod support;
mod surface_scenes;
mod time_scenes;
