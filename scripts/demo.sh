#!/usr/bin/env bash
# The main job on bundled data: installs what is missing, builds the `wavejets` command-line tool
# in Release, then runs it on the kitten scan (examples/Wavejets/data/kitten.xyz): curvature,
# position enhancement (gain 2), flattening (gain 0), inversion (gain -1), normal enhancement
# (gain 3) and twist (gain 2i). Writes the PLY files (open them in MeshLab or CloudCompare) and
# before/after PNG pictures to the folder given as $1 (default: out/). The pictures of the user
# manual (doc/Wavejets/fig) are the same, rendered with --width 560 --height 360.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)"
bash "$root/scripts/install_dependencies.sh"
build="$root/build/release"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DWAVEJETS_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build "$build" -j2 --target wavejets
wavejets="$build/demo/Wavejets/wavejets"
data="$root/examples/Wavejets/data/kitten.xyz"
run() { echo "\$ wavejets $*"; "$wavejets" "$@"; echo; }

echo "== Curvature of $data"
run curvature "$data" "$out/kitten_curvature.ply" --order 3
run render "$out/kitten_curvature.ply" "$out/kitten_curvature.png" --color-by mean_curvature

echo "== Position enhancement (gain 2): input left, result right"
run enhance-positions "$data" "$out/kitten_enhanced_positions.ply" --gain 2
run render --compare "$data" "$out/kitten_enhanced_positions.ply" "$out/kitten_enhanced_positions.png"

echo "== Flattening (gain 0): input left, result right"
run enhance-positions "$data" "$out/kitten_flattened_positions.ply" --gain 0
run render --compare "$data" "$out/kitten_flattened_positions.ply" "$out/kitten_flattened_positions.png"

echo "== Inversion (gain -1): input left, result right"
run enhance-positions "$data" "$out/kitten_inverted_positions.ply" --gain -1
run render --compare "$data" "$out/kitten_inverted_positions.ply" "$out/kitten_inverted_positions.png"

echo "== Normal enhancement (gain 3): input left, result right"
run enhance-normals "$data" "$out/kitten_enhanced_normals.ply" --gain 3
run render --compare "$data" "$out/kitten_enhanced_normals.ply" "$out/kitten_enhanced_normals.png"

echo "== Twist of the normals (gain 2i): input left, result right"
run enhance-normals "$data" "$out/kitten_twisted_normals.ply" --gain 0,2
run render --compare "$data" "$out/kitten_twisted_normals.ply" "$out/kitten_twisted_normals.png"

echo "Results in $out:"
ls -l "$out" | tail -n +2
