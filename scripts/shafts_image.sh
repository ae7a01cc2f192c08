#!/usr/bin/env bash
# docs/images/shafts_alps.png: the sunrise view 3 km above the Alps
# (assets/scenes/alps_sunrise.toml) with the terrain's light shafts (top) and without
# (bottom), 640 x 360 each, stacked by ImageMagick's `convert`.
#
#   scripts/shafts_image.sh [OUT.png]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/docs/images/shafts_alps.png}
command -v convert >/dev/null || { echo "ImageMagick's convert is needed to stack the two frames" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for shafts in on off; do
  "$root/scripts/render.sh" --scene "$root/assets/scenes/alps_sunrise.toml" \
    --width 640 --height 360 --shafts "$shafts" --out "$work/$shafts.png"
done
convert "$work/on.png" "$work/off.png" -append "$work/stacked.png"
mv "$work/stacked.png" "$out"
echo "wrote $out"
