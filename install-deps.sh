#!/bin/sh
# Installs the Debian 12 packages kdop needs to build, test and run, skipping those already
# installed. Run as root (the README's Quick start calls it first). Given package names, installs
# those instead (CI's sanitizer stage uses it for clang and LLVM).
set -eu

# glslang-tools: Debian 12's glslang CMake package refers to /usr/bin/glslangValidator, so
# find_package(glslang) fails without it even though kdop uses glslang only as a library.
# valgrind and gnuplot-nox: `kdop bench` (and its tests) run callgrind and draw charts with gnuplot.
# libglpk-dev and libqhull-dev: `kdop accuracy` solves the ideal clip as an exact LP (GLPK) and
# measures hull and k-DOP volumes (Qhull).
# libspirv-cross-c-shared-dev: SPIRV-Cross's static core library, which reflects shaders' interfaces.
# clang-format: the test format_is_applied checks the tree against .clang-format.
# nlohmann-json3-dev: every measurement writes its tables as JSON too (harness/table.h).
# libpng-dev: plain PNGs are read without loading OpenImageIO's codecs (images/png_read.h).
# fonts-dejavu-core: the font of the labels in `kdop taa`'s pictures (temporal/trail_picture.h).
# libopenmpi-dev and openmpi-bin: `mpirun -np R kdop optimize` shares a fit's frames over ranks
# (the build leaves MPI out where it is not installed).
# nodejs and npm: the WGSL tests compile with Tint, from the npm package `webgpu` (installed below).
# meson: a test builds a Meson project against kdop's pkg-config file (examples/meson_consumer).
# python3-jsonschema: a test validates the reflection JSON against docs/reflection.schema.json.
# chromium: a test opens kdop taa's report.html in it, headless and offline (tests/report_page_browser.py).
packages="
  build-essential cmake ninja-build pkg-config
  glslang-dev glslang-tools spirv-tools spirv-headers libspirv-cross-c-shared-dev
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libopenimageio-dev libpng-dev
  libglm-dev libfmt-dev libcli11-dev nlohmann-json3-dev
  libglpk-dev libqhull-dev
  libopenmpi-dev openmpi-bin
  libgtest-dev valgrind gnuplot-nox clang-format
  meson python3 python3-jsonschema chromium
  colobot-common-textures fonts-dejavu-core
"

# A node that is installed another way (NodeSource's nodejs carries its own npm) is kept.
command -v node >/dev/null 2>&1 || packages="$packages nodejs"
command -v npm >/dev/null 2>&1 || packages="$packages npm"

given_packages=false
if [ "$#" -gt 0 ]; then
  packages="$*"
  given_packages=true
fi

missing=""
for package in $packages; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing="$missing $package"
  fi
done

if [ -n "$missing" ]; then
  echo "install-deps.sh: installing$missing"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  # shellcheck disable=SC2086 # word splitting of the package list is intended
  apt-get install -y -qq --no-install-recommends $missing
fi

# Tint for the WGSL tests: the npm package `webgpu` (Dawn, with a null backend that compiles WGSL
# without a GPU) at the version and hashes tests/wgsl/package-lock.json pins, into
# tests/wgsl/node_modules (ignored by git), unless that version is there already.
if [ "$given_packages" = false ]; then
  wgsl="$(dirname "$0")/tests/wgsl"
  wanted="$(sed -n 's/.*"webgpu": "\(.*\)".*/\1/p' "$wgsl/package.json")"
  if ! grep -qs "\"version\": \"$wanted\"" "$wgsl/node_modules/webgpu/package.json"; then
    echo "install-deps.sh: installing the npm package webgpu@$wanted into $wgsl"
    (cd "$wgsl" && npm ci --no-audit --no-fund)
  fi
fi
