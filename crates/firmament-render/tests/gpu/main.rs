//! The GPU integration tests of `firmament-render`, in one test binary: one link instead of one
//! per file, and one device (`support::gpu()`) that every module's tests share and take turns on.
//! Run one module with `cargo test -p firmament-render --test gpu <module>::`, e.g. `sky::`.
//! They run on whatever adapter the machine has (Mesa's llvmpipe on CI) and fail, never skip,
//! when there is none.

mod aerial_perspective;
mod atmosphere;
mod bodies;
mod body_air;
mod body_light;
mod body_maps;
mod camera;
mod cloud_density;
mod cloud_slab;
mod clouds;
mod eclipse;
mod embed_target;
mod embedding;
mod empirical_sky;
mod envmap;
mod flare;
mod lut_rebuild;
mod medium_terms;
mod multiscattering;
mod night_sky;
mod objects;
mod pass_timing;
mod rings;
mod shadows;
mod sky;
mod sky_lighting;
mod small_bodies;
mod support;
mod surface;
mod thick_airs;
mod thick_slab;
mod user_material;
