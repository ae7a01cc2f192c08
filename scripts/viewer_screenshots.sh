#!/usr/bin/env bash
# The viewer's screenshots in docs/images/: the real window (under Xvfb when there is
# no display) at 2 m, 2 km, 20 km, 200 km and 20,000 km above the Ligurian Sea off Nice,
# looking north-north-west at the coast and the Alps, at noon and near sunset on the
# June solstice (UTC), with the default model. Each is `atmos view --frames 3
# --screenshot ...`: the image the window shows after three frames. Also the view
# `atmos` opens with (3 km above the Alps near sunset): docs/images/viewer_default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p atmos
run=(target/release/atmos)
if [ -z "${DISPLAY:-}" ]; then
  run=(xvfb-run -a -s "-screen 0 1600x900x24" target/release/atmos)
fi
place=(--latitude-deg 43.55 --longitude-deg 7.30 --heading-deg 330)
# altitude (m), pitch (deg), name
views=("2 3 2m" "2000 -2 2km" "20000 -6 20km" "200000 -20 200km" "20000000 -89 20000km")
times=("2024-06-21T11:33 noon" "2024-06-21T18:50 sunset")
for view in "${views[@]}"; do
  read -r altitude pitch name <<<"$view"
  for time in "${times[@]}"; do
    read -r utc label <<<"$time"
    out="docs/images/viewer_${name}_${label}.png"
    "${run[@]}" view --frames 3 --screenshot "$out" "${place[@]}" \
      --altitude-m "$altitude" --pitch-deg "$pitch" --utc "$utc"
  done
done
"${run[@]}" view --frames 3 --screenshot docs/images/viewer_default.png
