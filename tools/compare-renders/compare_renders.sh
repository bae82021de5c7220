#!/usr/bin/env bash
# Renders the list in renders.txt with two builds of mpr and compares every PNG pixel by pixel
# (png_diff.py): the check that a restructuring leaves every image unchanged.
#
#   tools/compare-renders/compare_renders.sh BASE [NEW_BUILD]
#
# BASE is a commit (built here in a temporary worktree, preset "test", only the programs the
# list runs) or an existing build folder of the older tree. NEW_BUILD is the build folder of
# the working tree (default build/test; the programs are built first). Data: $MPR_DATA_DIR or
# ../shared/data. Output: compare-renders-out/{base,new}/<name>/ under the working tree.
# Exits 0 when every image is identical.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
base=${1:?usage: compare_renders.sh BASE_COMMIT_OR_BUILD [NEW_BUILD]}
new_build=${2:-$top/build/test}
data=${MPR_DATA_DIR:-$top/../shared/data}
out=$top/compare-renders-out
targets=(mpr-gallery mpr-demo lightfield_refocus lightfield_multiperspective lightfield_temple
         lightfield_two_views leave_one_out mpr-render)

build_targets() { # build folder
  cmake --build "$1" -j2 --target "${targets[@]}" >"$1/compare-renders-build.log" 2>&1 ||
    { echo "compare_renders: build failed in $1 (see $1/compare-renders-build.log)" >&2; exit 1; }
}

if [ -d "$base" ]; then
  base_build=$(cd "$base" && pwd)
else
  sha=$(git -C "$top" rev-parse --verify "$base^{commit}")
  tree=$top/build/compare-$sha
  [ -d "$tree" ] || git -C "$top" worktree add --detach "$tree" "$sha" >/dev/null
  base_build=$tree/build/test
  [ -f "$base_build/CMakeCache.txt" ] ||
    cmake -S "$tree" -B "$base_build" -DCMAKE_BUILD_TYPE=Release -DMPR_DATA_DIR="$data" >/dev/null
  echo "building $sha in $base_build"
  build_targets "$base_build"
fi
echo "building the working tree in $new_build"
build_targets "$new_build"

rm -rf "$out"
while IFS= read -r line; do
  case "$line" in ''|'#'*) continue ;; esac
  name=${line%%:*}
  cmd=${line#*: }
  if [[ "$cmd" == *"{data}"* ]] && [ ! -d "$data/stanford" ]; then
    echo "skipped $name (no data in $data)"
    continue
  fi
  for side in base new; do
    bin=$base_build
    [ "$side" = new ] && bin=$new_build
    dir=$out/$side/$name
    mkdir -p "$dir"
    run=${cmd//\{bin\}/$bin}
    run=${run//\{data\}/$data}
    run=${run//\{out\}/$dir}
    start=$(date +%s%N)
    if ! (cd "$dir" && eval "$run" >"$dir.log" 2>&1); then
      echo "FAILED $side $name: $run (log: $dir.log)"
      exit 1
    fi
    tenths=$((($(date +%s%N) - start) / 100000000))
    printf '%-22s %-4s %4d.%d s\n' "$name" "$side" $((tenths / 10)) $((tenths % 10))
  done
done <"$here/renders.txt"
python3 "$here/png_diff.py" "$out/base" "$out/new"
