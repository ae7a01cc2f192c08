#!/usr/bin/env bash
# What recording a path in one run saves: one `atmos record` of N frames against N
# single-frame records (each a new process, device, pipelines and tables), interleaved
# round by round so that both see the same machine; prints each round's two times.
#
#   scripts/bench_record.sh PATH.toml N WIDTH HEIGHT ROUNDS
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/gpu_setup.sh"
use_lavapipe_without_gpu
give_runtime_dir
path=$1 n=$2 width=$3 height=$4 rounds=$5
cargo build --manifest-path "$root/Cargo.toml" --release --quiet -p atmos
atmos="${CARGO_TARGET_DIR:-$root/target}/release/atmos"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
record() { "$atmos" record "$path" --width "$width" --height "$height" --fps 2 "$@" >/dev/null 2>&1; }
echo "round  one run of $n frames (s)  $n runs of one frame (s)"
for round in $(seq 1 "$rounds"); do
  rm -rf "$work/one" "$work/each"
  start=$(date +%s.%N)
  record --out "$work/one" --frames "0..$n"
  middle=$(date +%s.%N)
  for i in $(seq 0 $((n - 1))); do record --out "$work/each" --frames "$i"; done
  end=$(date +%s.%N)
  cmp -s "$work/one/frame_000000.png" "$work/each/frame_000000.png" ||
    { echo "the two ways gave different frames" >&2; exit 1; }
  awk -v r="$round" -v a="$start" -v b="$middle" -v c="$end" 'BEGIN { printf "%5d  %24.2f  %24.2f\n", r, b - a, c - b }'
done
