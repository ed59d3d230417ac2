//! Build script: extracts the naked-eye stars (V ≤ 6.5) from the Hipparcos catalogue that the
//! `star-catalog` crate ships (its `hipp_bright` data: Hipparcos stars to V = 8, ESA 1997,
//! SP-1200) into a compact table that `astro::stars` embeds. See `docs/ASTRONOMY.md`, "Stars".

use std::error::Error;
use std::path::PathBuf;

/// The faintest V magnitude kept: the naked-eye limit of a dark sky.
const LIMITING_MAGNITUDE: f32 = 6.5;

/// Bytes per star: RA and Dec (f64, radians), V and B−V (f32), Hipparcos number (u32), all
/// little-endian.
const RECORD_BYTES: usize = 28;

fn main() -> Result<(), Box<dyn Error>> {
    println!("cargo::rerun-if-changed=build.rs");
    let catalog = star_catalog::Catalog::load_catalog("hipp_bright", LIMITING_MAGNITUDE + 0.001)
        .map_err(|e| format!("reading the Hipparcos data of the star-catalog crate: {e}"))?;
    let mut stars: Vec<_> = catalog
        .iter_stars()
        .filter(|s| s.magnitude() <= LIMITING_MAGNITUDE)
        .map(|s| (s.ra(), s.de(), s.magnitude(), s.bv(), s.id()))
        .collect();
    // Brightest first, then by Hipparcos number: a prefix of the table is a magnitude-limited
    // catalogue.
    stars.sort_by(|a, b| a.2.total_cmp(&b.2).then(a.4.cmp(&b.4)));
    let mut bytes = Vec::with_capacity(stars.len() * RECORD_BYTES);
    for (ra, dec, v, bv, hip) in stars {
        let hip = u32::try_from(hip).map_err(|_| format!("Hipparcos number {hip} out of range"))?;
        bytes.extend_from_slice(&ra.to_le_bytes());
        bytes.extend_from_slice(&dec.to_le_bytes());
        bytes.extend_from_slice(&v.to_le_bytes());
        bytes.extend_from_slice(&bv.to_le_bytes());
        bytes.extend_from_slice(&hip.to_le_bytes());
    }
    let out = PathBuf::from(std::env::var("OUT_DIR")?).join("bright_stars.bin");
    std::fs::write(out, bytes)?;
    Ok(())
}
