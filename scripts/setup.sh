#!/usr/bin/env bash
# Installs what firmament's tests need beyond a Rust toolchain, when missing (Debian/Ubuntu, as
# root; elsewhere it says what to install):
# - Mesa's EGL/GL drivers: llvmpipe, the software adapter the GPU tests use without a GPU;
# - Xvfb and the X client libraries winit loads: the viewer's tests run it on a virtual display.
set -euo pipefail

missing=()
# Read once: `ldconfig -p | grep -q` can fail under pipefail when grep stops reading early.
libraries="$(ldconfig -p 2>/dev/null || true)"
grep -q 'libEGL_mesa.so' <<<"$libraries" || missing+=(libegl1 libegl-mesa0 libgl1-mesa-dri)
command -v Xvfb >/dev/null || missing+=(xvfb)
for lib in libX11.so.6 libXcursor.so.1 libXrandr.so.2 libXi.so.6 libxkbcommon-x11.so.0; do
  grep -q "$lib" <<<"$libraries" || missing+=("$lib")
done
[ ${#missing[@]} -eq 0 ] && exit 0

# Library file names to Debian package names.
packages=()
for item in "${missing[@]}"; do
  case "$item" in
    libX11.so.6) packages+=(libx11-6) ;;
    libXcursor.so.1) packages+=(libxcursor1) ;;
    libXrandr.so.2) packages+=(libxrandr2) ;;
    libXi.so.6) packages+=(libxi6) ;;
    libxkbcommon-x11.so.0) packages+=(libxkbcommon-x11-0) ;;
    *) packages+=("$item") ;;
  esac
done

if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
  echo "setup: installing ${packages[*]}" >&2
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${packages[@]}" >/dev/null
else
  echo "warning: missing ${packages[*]} (Debian/Ubuntu package names); GPU and viewer tests will fail" >&2
fi
