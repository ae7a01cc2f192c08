#!/usr/bin/env bash
# Frames per second of `atmos record` against one `atmos render` per frame: the record
# keeps one renderer and each model's tables across frames, a render per frame starts a
# process, an adapter and the tables each time. Interleaved runs, medians, on whatever
# GPU or software Vulkan the environment gives (docs/recording.md has the numbers).
#
#   scripts/bench_record.sh [ATMOS] [MODEL] [FRAMES] [WIDTH] [HEIGHT] [RUNS]
#
# Defaults: target/debug/atmos, bruneton, 8 frames, 160 x 90 px, 3 runs. Prints each
# run's seconds per frame and the medians' ratio.
set -euo pipefail
atmos=${1:-target/debug/atmos}
model=${2:-bruneton}
frames=${3:-8}
width=${4:-160}
height=${5:-90}
runs=${6:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# One path: the sun sinks a degree a frame over a fixed camera (tables stay valid).
last=$((frames - 1))
cat >"$work/path.toml" <<TOML
version = 1
fps = 1
[[keyframe]]
time_s = 0
latitude_deg = 46.0
longitude_deg = 7.8
altitude_m = 1000
heading_deg = 250
pitch_deg = 5
sun_elevation_deg = 20
sun_azimuth_deg = 250
model = "$model"
[[keyframe]]
time_s = $last
sun_elevation_deg = $((20 - last))
TOML

now() { date +%s.%N; }
record=() render=()
for run in $(seq "$runs"); do
  t0=$(now)
  "$atmos" record "$work/path.toml" --out "$work/rec$run" --width "$width" \
    --height "$height" >/dev/null 2>&1
  t1=$(now)
  for i in $(seq 0 "$last"); do
    "$atmos" render --model "$model" --latitude-deg 46.0 --longitude-deg 7.8 \
      --altitude-m 1000 --view-zenith-deg 85 --view-azimuth-deg -250 \
      --sun-zenith-deg $((70 + i)) --sun-azimuth-deg -250 --fov-deg 60 \
      --width "$width" --height "$height" --out "$work/render$run-$i.png" >/dev/null 2>&1
  done
  t2=$(now)
  record+=("$(echo "($t1 - $t0) / $frames" | bc -l)")
  render+=("$(echo "($t2 - $t1) / $frames" | bc -l)")
  printf 'run %d: record %.3f s/frame, render per frame %.3f s/frame\n' \
    "$run" "${record[-1]}" "${render[-1]}"
done
median() { printf '%s\n' "$@" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}'; }
mr=$(median "${record[@]}")
mp=$(median "${render[@]}")
printf '%s %d frames %dx%d: record %.3f s/frame, render per frame %.3f s/frame, ratio %.2f\n' \
  "$model" "$frames" "$width" "$height" "$mr" "$mp" "$(echo "$mp / $mr" | bc -l)"
