# Sourced by the scripts: install_missing_packages PACKAGE... installs, through apt, whichever of
# the Debian packages is not installed yet (as root, or through sudo), and nothing else.

install_missing_packages() {
  local missing=() package
  for package in "$@"; do
    if ! dpkg -s "$package" 2>/dev/null | grep -q '^Status: install ok installed$'; then
      missing+=("$package")
    fi
  done
  ((${#missing[@]})) || return 0

  echo "installing ${missing[*]}"
  local as_root=()
  if ((EUID != 0)); then
    command -v sudo >/dev/null || { echo "run as root to install: ${missing[*]}" >&2; return 1; }
    as_root=(sudo)
  fi
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
  "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive \
    apt-get install -y -q --no-install-recommends "${missing[@]}"
}

# Everything the project builds with (scripts/setup; scripts/fuzz adds clang to it).
project_packages=(
  # toolchain, tests, benchmarks, plots
  build-essential cmake ninja-build
  libgtest-dev libgmock-dev libbenchmark-dev
  python3 python3-numpy python3-matplotlib
  # distributed studies and renders (scripts/study, scripts/render-distributed): Dask, and
  # OpenImageIO's Python module to read their images
  python3-distributed python3-dask python3-openimageio
  # the renderer: ray tracing, images (PNG, EXR; stb_image for TGA, JPEG and the other formats
  # pbrt-v4 reads with it; OpenImageIO for the rest), threads, command line,
  # scene data, formatting,
  # Sobol' direction numbers (Boost.Random's table, header-only)
  libembree-dev libopenexr-dev libopenimageio-dev openimageio-tools libtbb-dev
  libcli11-dev nlohmann-json3-dev libfmt-dev libboost-dev libpng-dev libstb-dev
  # participating media: NanoVDB grids (header-only) and the zlib its reader inflates them with
  libnanovdb-dev zlib1g-dev
)
