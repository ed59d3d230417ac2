#!/usr/bin/env python3
"""Build firmament's Earth surface map (crates/firmament-scene/data/earth-surface.png).

Pure standard library (Python >= 3.11): zlib, struct, json, math.

Output: 1440x720 RGBA 8-bit PNG, equirectangular (plate carree). Texel (i, j) has
its centre at longitude -180 + (i + 0.5) * 0.25 deg and latitude 90 - (j + 0.5) * 0.25 deg.
  * A   = water fraction of the texel, 0 (all land) .. 255 (all open water),
          from the Natural Earth 1:50m land polygons, 4x4 supersampled, plus the
          Antarctic ice shelves (white in the NE1 raster, sea in the polygons) unless
          --no-ice-shelves.
  * RGB = diffuse (Lambertian) albedo, sRGB-encoded. Land from the Natural Earth I
          shaded-relief raster mapped to physical albedos; water a fixed deep-ocean
          body reflectance; coast texels blend the two by the water fraction.

Inputs (see crates/firmament-scene/data/README.md):
  NE1_PNG   cartopy/data/raster/natural_earth/50-natural-earth-1-downsampled.png
            from the cartopy 0.26.0 wheel:
              pip download cartopy==0.26.0 --no-deps --only-binary=:all:
              unzip -j cartopy-0.26.0-*.whl \\
                cartopy/data/raster/natural_earth/50-natural-earth-1-downsampled.png
  LAND_JSON land-50m.json from the npm package world-atlas 2.0.2:
              npm pack world-atlas@2.0.2 && tar xzf world-atlas-2.0.2.tgz
              (gives package/land-50m.json)

Usage:
  python3 scripts/earth_surface.py NE1_PNG LAND_JSON OUTPUT_PNG [--preview RGB_PNG] [--no-ice-shelves]
"""

from __future__ import annotations

import argparse
import json
import math
import struct
import zlib

# Output grid and supersampling.
OUT_W, OUT_H = 1440, 720
SS = 4  # samples per texel along each axis
SW, SH = OUT_W * SS, OUT_H * SS  # sample grid
SAMPLES_PER_DEG = SW / 360.0  # == SH / 180

# Deep-ocean diffuse (body) reflectance, linear sRGB. Glint/Fresnel are the renderer's.
WATER_ALBEDO = (0.006, 0.012, 0.035)

# Land albedo mapping (see albedo_from_tint).
LAND_K = 0.68  # coloured land: luminance Y_a = LAND_K * Y_tint ** LAND_GAMMA
LAND_GAMMA = 3.0  # expands Natural Earth I's pale tints (forest ~0.53, desert ~0.8 luminance)
CHROMA_GAMMA = 2.0  # chromaticity from tint ** CHROMA_GAMMA: restores saturation
ICE_K = 0.90  # near-white (ice sheet) texels: albedo = ICE_K * tint
ICE_MIN_LO, ICE_MIN_HI = 0.60, 0.70  # smoothstep on the min linear channel
ICE_BLUE_LO, ICE_BLUE_HI = 0.02, 0.05  # smoothstep on (b - r), linear: ice is bluish white
# ...or very bright and at most slightly yellow (NE1's sunlit ice highlights are neutral;
# its brightest desert pixels have b - r ~ -0.1 .. -0.17).
ICE_BRIGHT_LO, ICE_BRIGHT_HI = 0.82, 0.88  # smoothstep on the min linear channel
ICE_NEUTRAL_LO, ICE_NEUTRAL_HI = -0.06, -0.02  # smoothstep on (b - r)
ICE_SHELF_MAX_LAT = -60.0  # --ice-shelves: ice-white NE1 sea south of this counts as land


# --------------------------------------------------------------------------- PNG I/O


def read_png_rgb(path: str) -> tuple[int, int, list[bytearray]]:
    """Decode a non-interlaced 8-bit RGB/RGBA PNG; returns (w, h, rows of RGB bytes)."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(f"{path}: not a PNG")
    pos, idat = 8, []
    w = h = bit_depth = colour_type = interlace = None
    while pos < len(data):
        (n,) = struct.unpack(">I", data[pos : pos + 4])
        ctype = data[pos + 4 : pos + 8]
        chunk = data[pos + 8 : pos + 8 + n]
        pos += 12 + n
        if ctype == b"IHDR":
            w, h, bit_depth, colour_type, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
        elif ctype == b"IDAT":
            idat.append(chunk)
        elif ctype == b"IEND":
            break
    if bit_depth != 8 or colour_type not in (2, 6) or interlace != 0:
        raise ValueError(f"{path}: need 8-bit RGB/RGBA non-interlaced PNG")
    bpp = 3 if colour_type == 2 else 4
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    rows, prev, p = [], bytearray(stride), 0
    for _ in range(h):
        ftype = raw[p]
        cur = bytearray(raw[p + 1 : p + 1 + stride])
        p += 1 + stride
        if ftype == 1:  # Sub
            for i in range(bpp, stride):
                cur[i] = (cur[i] + cur[i - bpp]) & 255
        elif ftype == 2:  # Up
            for i in range(stride):
                cur[i] = (cur[i] + prev[i]) & 255
        elif ftype == 3:  # Average
            for i in range(stride):
                left = cur[i - bpp] if i >= bpp else 0
                cur[i] = (cur[i] + ((left + prev[i]) >> 1)) & 255
        elif ftype == 4:  # Paeth
            for i in range(stride):
                a = cur[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                pa, pb, pc = abs(b - c), abs(a - c), abs(a + b - 2 * c)
                pred = a if (pa <= pb and pa <= pc) else (b if pb <= pc else c)
                cur[i] = (cur[i] + pred) & 255
        elif ftype != 0:
            raise ValueError(f"{path}: bad filter type {ftype}")
        rows.append(cur)
        prev = cur
    if bpp == 4:
        rows = [bytearray(b for k, b in enumerate(r) if k % 4 != 3) for r in rows]
    return w, h, rows


def write_png(path: str, w: int, h: int, rows: list[bytes], colour_type: int) -> None:
    """Write an 8-bit PNG (colour type 2 = RGB, 6 = RGBA), filter type 0 on every row."""

    def chunk(ctype: bytes, body: bytes) -> bytes:
        return struct.pack(">I", len(body)) + ctype + body + struct.pack(">I", zlib.crc32(ctype + body))

    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    ihdr = struct.pack(">IIBBBBB", w, h, 8, colour_type, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n")
        f.write(chunk(b"IHDR", ihdr))
        f.write(chunk(b"sRGB", b"\x00"))  # perceptual; RGB is sRGB-encoded
        f.write(chunk(b"IDAT", zlib.compress(raw, 9)))
        f.write(chunk(b"IEND", b""))


# --------------------------------------------------------------------------- colour


def srgb_to_linear(c: float) -> float:
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def linear_to_srgb8(x: float) -> int:
    x = min(max(x, 0.0), 1.0)
    s = x * 12.92 if x <= 0.0031308 else 1.055 * x ** (1.0 / 2.4) - 0.055
    return int(round(s * 255.0))


def smoothstep(e0: float, e1: float, x: float) -> float:
    t = min(max((x - e0) / (e1 - e0), 0.0), 1.0)
    return t * t * (3.0 - 2.0 * t)


def ice_weight(r: float, g: float, b: float) -> float:
    """1 for near-white, bluish-white or neutral (ice-sheet) tints; 0 for coloured land."""
    m = min(r, g, b)
    bluish = smoothstep(ICE_MIN_LO, ICE_MIN_HI, m) * smoothstep(ICE_BLUE_LO, ICE_BLUE_HI, b - r)
    bright = smoothstep(ICE_BRIGHT_LO, ICE_BRIGHT_HI, m) * smoothstep(ICE_NEUTRAL_LO, ICE_NEUTRAL_HI, b - r)
    return max(bluish, bright)


def albedo_from_tint(r: float, g: float, b: float) -> tuple[float, float, float]:
    """Map a linear Natural Earth I tint to a linear Lambertian albedo.

    Coloured land: luminance Y_a = LAND_K * Y ** LAND_GAMMA, chromaticity that of
    c ** CHROMA_GAMMA. The cartographic tints are pale (forest ~0.53 luminance, desert
    ~0.8), so a plain scale cannot make forests dark and deserts bright at once; the
    power law spreads them to ~0.1 vs ~0.35, and the chroma exponent restores some of
    the saturation the pastel tints lack. Ice: a = ICE_K * c. The two blend by
    ice_weight.
    """
    w = ice_weight(r, g, b)
    y = luminance((r, g, b))
    d = (r**CHROMA_GAMMA, g**CHROMA_GAMMA, b**CHROMA_GAMMA)
    yd = luminance(d)
    scale = LAND_K * y**LAND_GAMMA / yd if yd > 0.0 else 0.0
    out = []
    for c, dc in zip((r, g, b), d):
        out.append(min((1.0 - w) * scale * dc + w * ICE_K * c, 0.95))
    return out[0], out[1], out[2]


def luminance(c) -> float:
    return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]


# --------------------------------------------------------------------------- TopoJSON


def decode_topojson_land(path: str) -> list[list[list[tuple[float, float]]]]:
    """Return the polygons of object `land` as lists of rings of (lon, lat)."""
    with open(path) as f:
        topo = json.load(f)
    tr = topo.get("transform")
    arcs = []
    for arc in topo["arcs"]:
        pts = []
        if tr:
            (sx, sy), (tx, ty) = tr["scale"], tr["translate"]
            x = y = 0
            for dx, dy in arc:  # quantised, delta-encoded
                x += dx
                y += dy
                pts.append((x * sx + tx, y * sy + ty))
        else:
            pts = [(float(p[0]), float(p[1])) for p in arc]
        arcs.append(pts)

    def ring(indices: list[int]) -> list[tuple[float, float]]:
        out: list[tuple[float, float]] = []
        for i in indices:
            pts = arcs[i] if i >= 0 else arcs[~i][::-1]
            out.extend(pts if not out else pts[1:])  # arcs share their end points
        return out

    polys = []

    def add(geom):
        t = geom["type"]
        if t == "GeometryCollection":
            for g in geom["geometries"]:
                add(g)
        elif t == "Polygon":
            polys.append([ring(r) for r in geom["arcs"]])
        elif t == "MultiPolygon":
            for p in geom["arcs"]:
                polys.append([ring(r) for r in p])

    add(topo["objects"]["land"])
    return polys


def unwrap_ring(ring: list[tuple[float, float]]) -> tuple[list[tuple[float, float]], int]:
    """Make longitudes continuous across the antimeridian.

    Returns the ring in sample-grid coordinates (X right, Y down) and the ring's net
    number of turns around the pole (0 for an ordinary ring, +-1 for a ring such as
    Antarctica's that encircles a pole).
    """
    out = []
    off = 0.0
    prev_lon = None
    for lon, lat in ring:
        if prev_lon is not None:
            d = lon - prev_lon
            if d > 180.0:
                off -= 360.0
            elif d < -180.0:
                off += 360.0
        prev_lon = lon
        out.append(((lon + off + 180.0) * SAMPLES_PER_DEG, (90.0 - lat) * SAMPLES_PER_DEG))
    turns = round(off / 360.0)
    if out[0] == out[-1]:
        out.pop()
    return out, turns


# --------------------------------------------------------------------------- rasteriser


def rasterise_land(polys) -> tuple[list[list[int]], dict]:
    """Land coverage per output texel, 0..SS*SS samples, even-odd fill per polygon.

    Each polygon is filled on its own (even-odd over its rings) and the results are
    unioned, so overlapping or touching polygons never cancel. Rings crossing the
    antimeridian are unwrapped and drawn at the longitude shifts that reach the map;
    a ring encircling a pole is closed along the pole (the map's top or bottom edge).
    """
    crossings: list[list[tuple[int, float]]] = [[] for _ in range(SH)]
    info = {"antimeridian_rings": 0, "pole_rings": []}
    for pid, poly in enumerate(polys):
        rings = []
        for ring in poly:
            pts, turns = unwrap_ring(ring)
            if turns != 0:
                mean_lat = sum(lat for _, lat in ring) / len(ring)
                pole_y = float(SH) if mean_lat < 0 else 0.0
                x_end, x_start = pts[-1][0], pts[0][0]
                pts = pts + [(x_end, pole_y), (x_start, pole_y)]
                info["pole_rings"].append(("south" if mean_lat < 0 else "north", len(ring)))
            xs = [p[0] for p in pts]
            if min(xs) < 0.0 or max(xs) > SW:
                info["antimeridian_rings"] += 1
            rings.append(pts)
        xmin = min(p[0] for r in rings for p in r)
        xmax = max(p[0] for r in rings for p in r)
        shifts = [k * SW for k in (-2, -1, 0, 1, 2) if xmin + k * SW < SW and xmax + k * SW > 0]
        for pts in rings:
            n = len(pts)
            for k in range(n):
                x0, y0 = pts[k]
                x1, y1 = pts[(k + 1) % n]
                if y0 == y1:
                    continue
                if y0 > y1:
                    x0, y0, x1, y1 = x1, y1, x0, y0
                # sample rows t whose centre t + 0.5 lies in [y0, y1)
                t0 = max(math.ceil(y0 - 0.5), 0)
                t1 = min(math.ceil(y1 - 0.5), SH)
                if t0 >= t1:
                    continue
                slope = (x1 - x0) / (y1 - y0)
                for t in range(t0, t1):
                    x = x0 + (t + 0.5 - y0) * slope
                    for sh in shifts:
                        crossings[t].append((pid, x + sh))

    coverage = [[0] * OUT_W for _ in range(OUT_H)]
    for j in range(OUT_H):
        acc = 0
        for sub in range(SS):
            row = bytearray(SW)
            xs = sorted(crossings[j * SS + sub])
            for k in range(0, len(xs) - 1, 2):
                (pa, xa), (pb, xb) = xs[k], xs[k + 1]
                if pa != pb:
                    raise ValueError(f"odd crossing count for polygon {pa} in sample row {j * SS + sub}")
                s0 = max(math.ceil(xa - 0.5), 0)
                s1 = min(math.ceil(xb - 0.5), SW)
                if s1 > s0:
                    row[s0:s1] = b"\x01" * (s1 - s0)
            if len(xs) % 2:
                raise ValueError(f"odd crossing count in sample row {j * SS + sub}")
            acc += int.from_bytes(row, "little")  # SS rows of 0/1 bytes: no carries
        # sum groups of SS consecutive bytes (sample columns of a texel)
        v = acc
        for k in range(1, SS):
            v += acc >> (8 * k)
        b = v.to_bytes(SW + 8, "little")
        coverage[j] = list(b[0 : SW : SS])
    return coverage, info


# --------------------------------------------------------------------------- land colour


def decode_linear(ne_w, ne_h, ne_rows):
    """NE1 rows of sRGB bytes -> flat list of linear (r, g, b), row-major."""
    lut = [srgb_to_linear(v / 255.0) for v in range(256)]
    return [
        (lut[row[3 * i]], lut[row[3 * i + 1]], lut[row[3 * i + 2]]) for row in ne_rows for i in range(ne_w)
    ]


def ice_shelf_field(ne_w, ne_h, col):
    """Per NE1 pixel: ice weight of its tint south of ICE_SHELF_MAX_LAT, else 0.

    The 1:50m land polygons follow Antarctica's grounding line, so the floating ice
    shelves (Ross, Ronne-Filchner, Amery, ...) are sea in them; NE1 paints them white.
    """
    out = [0.0] * (ne_w * ne_h)
    for j in range(ne_h):
        lat = 90.0 - (j + 0.5) * 180.0 / ne_h
        if lat >= ICE_SHELF_MAX_LAT:
            continue
        for i in range(ne_w):
            k = j * ne_w + i
            out[k] = ice_weight(*col[k])
    return out


def land_colour_field(ne_w, ne_h, col, land_frac_src):
    """Linear NE1 colours with sea-coloured / sea-covered pixels replaced by nearby land.

    Natural Earth I paints the sea blue and its coastline differs slightly from the
    1:50m polygons; so that coast texels do not pick up the sea's blue, NE1 pixels that
    are not clearly land (land fraction x 'not sea-blue' < 0.5) are filled by dilating
    the neighbouring land colours outwards (8 passes) before resampling.
    """
    n = ne_w * ne_h
    valid = bytearray(n)
    for k in range(n):
        r, g, b = col[k]
        # NE1 sea is strongly blue (b - r ~ 0.35..0.5 linear); land <= ~0.15 (ice).
        not_sea = min(max((0.30 - (b - r)) / 0.12, 0.0), 1.0)
        valid[k] = land_frac_src[k] * not_sea >= 0.5
    land_cols = sorted((luminance(col[k]), col[k]) for k in range(n) if valid[k])
    default = land_cols[len(land_cols) // 2][1]
    filled = list(col)
    for _ in range(8):
        new_valid = bytearray(valid)
        changed = 0
        for j in range(ne_h):
            for i in range(ne_w):
                k = j * ne_w + i
                if valid[k]:
                    continue
                sr = sg = sb = sw = 0.0
                for dj in (-1, 0, 1):
                    jj = j + dj
                    if jj < 0 or jj >= ne_h:
                        continue
                    for di in (-1, 0, 1):
                        kk = jj * ne_w + (i + di) % ne_w
                        if valid[kk]:
                            c = filled[kk]
                            sr += c[0]
                            sg += c[1]
                            sb += c[2]
                            sw += 1.0
                if sw > 0:
                    filled[k] = (sr / sw, sg / sw, sb / sw)
                    new_valid[k] = 1
                    changed += 1
        valid = new_valid
        if not changed:
            break
    for k in range(n):
        if not valid[k]:
            filled[k] = default
    return filled


def bilinear(field, fw, fh, lon, lat):
    """Bilinear sample of a plate-carree field (pixel centres at half-pixel offsets)."""
    u = (lon + 180.0) / 360.0 * fw - 0.5
    v = (90.0 - lat) / 180.0 * fh - 0.5
    i0 = math.floor(u)
    j0 = math.floor(v)
    fu, fv = u - i0, v - j0
    j0c, j1c = min(max(j0, 0), fh - 1), min(max(j0 + 1, 0), fh - 1)
    i0w, i1w = i0 % fw, (i0 + 1) % fw
    c00, c10 = field[j0c * fw + i0w], field[j0c * fw + i1w]
    c01, c11 = field[j1c * fw + i0w], field[j1c * fw + i1w]
    return tuple(
        (c00[c] * (1 - fu) + c10[c] * fu) * (1 - fv) + (c01[c] * (1 - fu) + c11[c] * fu) * fv for c in range(3)
    )


# --------------------------------------------------------------------------- main


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("ne1_png", help="Natural Earth I 720x360 RGB PNG (cartopy 0.26.0)")
    ap.add_argument("land_json", help="world-atlas 2.0.2 land-50m.json (TopoJSON)")
    ap.add_argument("output_png", help="output 1440x720 RGBA PNG")
    ap.add_argument("--preview", help="also write an RGB-only PNG (alpha dropped) here")
    ap.add_argument(
        "--no-ice-shelves",
        dest="ice_shelves",
        action="store_false",
        help="alpha strictly from the land polygons: leave Antarctic ice shelves as open water",
    )
    args = ap.parse_args()

    polys = decode_topojson_land(args.land_json)
    coverage, info = rasterise_land(polys)
    print(
        f"land polygons: {len(polys)}, rings: {sum(len(p) for p in polys)}, "
        f"antimeridian-crossing rings: {info['antimeridian_rings']}, pole-encircling rings: {info['pole_rings']}"
    )
    full = SS * SS
    print(
        f"land fraction of top row {sum(coverage[0]) / (full * OUT_W):.3f}, "
        f"bottom row {sum(coverage[-1]) / (full * OUT_W):.3f}"
    )

    ne_w, ne_h, ne_rows = read_png_rgb(args.ne1_png)
    fx, fy = OUT_W // ne_w, OUT_H // ne_h
    if fx * ne_w != OUT_W or fy * ne_h != OUT_H:
        raise ValueError("NE1 raster size must divide 1440x720")
    col = decode_linear(ne_w, ne_h, ne_rows)
    shelf = ice_shelf_field(ne_w, ne_h, col) if args.ice_shelves else [0.0] * (ne_w * ne_h)
    land_frac_src = []
    for j in range(ne_h):
        for i in range(ne_w):
            f = sum(coverage[j * fy + b][i * fx + a] for b in range(fy) for a in range(fx)) / (full * fx * fy)
            land_frac_src.append(f + (1.0 - f) * shelf[j * ne_w + i])
    field = land_colour_field(ne_w, ne_h, col, land_frac_src)
    shelf_field = [(s, s, s) for s in shelf]

    rows_rgba, rows_rgb = [], []
    sum_w = 0.0
    sum_alb = [0.0, 0.0, 0.0]
    sum_water = 0.0
    sum_shelf = 0.0
    sum_land_w = 0.0
    sum_land_alb = [0.0, 0.0, 0.0]
    cats = {"ice (w>0.5)": [0.0, 0.0, 0.0, 0.0]}
    for j in range(OUT_H):
        lat = 90.0 - (j + 0.5) * 180.0 / OUT_H
        wlat = math.cos(math.radians(lat))
        out = bytearray(4 * OUT_W)
        for i in range(OUT_W):
            lon = -180.0 + (i + 0.5) * 360.0 / OUT_W
            land = coverage[j][i] / full
            if args.ice_shelves and lat < ICE_SHELF_MAX_LAT + 1.0 and land < 1.0:
                s = bilinear(shelf_field, ne_w, ne_h, lon, lat)[0]
                if s > 0.0:
                    sum_shelf += wlat * (1.0 - land) * s
                    land += (1.0 - land) * s
            water = 1.0 - land
            if land > 0.0:
                c = bilinear(field, ne_w, ne_h, lon, lat)
                la = albedo_from_tint(*c)
                wa = land * wlat
                sum_land_w += wa
                for k in range(3):
                    sum_land_alb[k] += wa * la[k]
                if ice_weight(*c) > 0.5:
                    cat = cats["ice (w>0.5)"]
                    cat[0] += wa
                    for k in range(3):
                        cat[k + 1] += wa * la[k]
                alb = [land * la[k] + water * WATER_ALBEDO[k] for k in range(3)]
            else:
                alb = list(WATER_ALBEDO)
            sum_w += wlat
            sum_water += wlat * water
            for k in range(3):
                sum_alb[k] += wlat * alb[k]
            o = 4 * i
            out[o] = linear_to_srgb8(alb[0])
            out[o + 1] = linear_to_srgb8(alb[1])
            out[o + 2] = linear_to_srgb8(alb[2])
            out[o + 3] = int(round(255.0 * water))
        rows_rgba.append(out)
        if args.preview:
            rows_rgb.append(bytes(b for k, b in enumerate(out) if k % 4 != 3))

    write_png(args.output_png, OUT_W, OUT_H, rows_rgba, 6)
    if args.preview:
        write_png(args.preview, OUT_W, OUT_H, rows_rgb, 2)

    def fmt(v):
        return "(" + ", ".join(f"{x:.4f}" for x in v) + ")"

    print(f"image: {OUT_W}x{OUT_H} RGBA8 -> {args.output_png}")
    print(f"global area-weighted mean albedo (linear RGB): {fmt([s / sum_w for s in sum_alb])}")
    print(f"global area-weighted water fraction: {sum_water / sum_w:.4f}")
    if args.ice_shelves:
        km2 = 4.0 * math.pi * 6371.0**2 * sum_shelf / sum_w
        print(f"Antarctic ice shelves added as land (white NE1 sea south of 60S): {km2 / 1e6:.2f} million km^2")
    print(f"mean land albedo (linear RGB, area-weighted): {fmt([s / sum_land_w for s in sum_land_alb])}")
    for name, cat in cats.items():
        if cat[0] > 0:
            print(
                f"  {name}: {cat[0] / sum_land_w:.3f} of land area, mean albedo {fmt([c / cat[0] for c in cat[1:]])}"
            )


if __name__ == "__main__":
    main()
