#!/usr/bin/env bash
# Makes assets/earth/land_mask.png (the 1 km land/sea mask) from the PyPI wheel
# global-land-mask 1.0.0, converted by scripts/land_mask.py (Python standard library
# only). Deterministic and re-runnable: the wheel is pinned by version and SHA-256 and kept
# in the work folder (default target/earth-data, or $ATMOS_EARTH_WORK). See
# assets/CREDITS.md and docs/terrain.md.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
work="${ATMOS_EARTH_WORK:-$root/target/earth-data}"
out="$root/assets/earth"

version=1.0.0
wheel="global_land_mask-${version}-py3-none-any.whl"
sha256=07751fbb4e3834ee508a84ea64d9bd5340fbd0a8c951e24b43c323fcc670bb62

mkdir -p "$work" "$out"
cd "$work"
if [ ! -f "$wheel" ]; then
  echo "downloading global-land-mask $version (PyPI)" >&2
  python3 -m pip download --quiet --no-deps --dest . "global-land-mask==$version"
fi
echo "$sha256  $wheel" | sha256sum --check --quiet || {
  echo "$wheel: SHA-256 differs from the pinned one; delete it and re-run" >&2
  exit 1
}
python3 "$root/scripts/land_mask.py" "$wheel" "$out/land_mask.png"
ls -l "$out/land_mask.png" >&2
sha256sum "$out/land_mask.png"
