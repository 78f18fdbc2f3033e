#!/usr/bin/env bash
# result_checksums.sh BUILD_DIR OUT.txt: sha256 of what the package computes, for refactorings that
# must leave the results bitwise unchanged (compare OUT.txt before and after, same compiler and flags).
#   - the four point-set functions through the `wavejets` tool on the bundled kitten scan and on a
#     100,000-point sample of the bunny (scripts/sample_mesh.py, fixed seed): normals (k 20), curvature
#     (k 30), enhance-positions (k 40, gain 2), enhance-normals (k 40, gain 2i), enhance-positions along
#     the input normals with consistent normals (k 40, gain 3);
#   - test_public_api_results' records (every public function, the options that change the computation).
# Needs the targets `wavejets` and `test_public_api_results` built in BUILD_DIR, and python3.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
out="$(realpath -m "$2")"
work=/tmp/wavejets_result_checksums   # a fixed folder: the PLY comments name the input path
rm -rf "$work" && mkdir -p "$work"
cp "$root/examples/Wavejets/data/kitten.xyz" "$work/kitten.xyz"
python3 "$root/scripts/sample_mesh.py" "$root/examples/Wavejets/data/bunny00.off" 100000 12345 "$work/bunny100k.xyz"
tool="$build/demo/Wavejets/wavejets"
cd "$work"
for n in kitten bunny100k; do
  "$tool" normals $n.xyz $n.normals.ply --k 20 --quiet
  "$tool" curvature $n.xyz $n.curv.ply --k 30 --quiet
  "$tool" enhance-positions $n.xyz $n.pos.ply --k 40 --gain 2 --quiet
  "$tool" enhance-normals $n.normals.ply $n.nf.ply --k 40 --gain 0,2 --quiet
  "$tool" enhance-positions $n.normals.ply $n.posn.ply --k 40 --gain 3 --along-input-normals --consistent-normals --quiet
done
(cd "$root/test/Wavejets" && WAVEJETS_OUTPUT_DIR="$work" "$build/test/Wavejets/test_public_api_results" > /dev/null)
sha256sum ./*.ply public_api_results.txt > "$out"
echo "checksums of $(ls ./*.ply | wc -l) outputs and the public API records written to $out"
