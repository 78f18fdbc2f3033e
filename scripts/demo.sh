#!/usr/bin/env bash
# The main job on bundled data: installs what is missing, builds in Release, then on the kitten
# scan estimates curvature (prints statistics), enhances positions (gain 2) and normals (gain 3).
# Writes PLY files (open them in MeshLab or CloudCompare) to the folder given as $1 (default: out/).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(mkdir -p "${1:-$root/out}" && cd "${1:-$root/out}" && pwd)"
bash "$root/scripts/install_dependencies.sh"
build="$root/build/release"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Release -DWAVEJETS_BUILD_BENCHMARKS=OFF > /dev/null
examples="wavejet_estimate_curvatures_example wavejet_enhance_positions_example wavejet_enhance_normals_example"
cmake --build "$build" -j2 --target $examples
data="$root/examples/Wavejets/data/kitten.xyz"
bin="$build/examples/Wavejets"
echo "== Curvature of $data"
"$bin/wavejet_estimate_curvatures_example" "$data" "$out/kitten_curvatures.ply"
echo "== Position enhancement (gain 2)"
"$bin/wavejet_enhance_positions_example" "$data" "$out/kitten_enhanced_positions.ply" 2
echo "== Normal enhancement (gain 3)"
"$bin/wavejet_enhance_normals_example" "$data" "$out/kitten_enhanced_normals.ply" 3
echo "Results in $out"
