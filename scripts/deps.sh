#!/usr/bin/env bash
# seamquad: the Debian packages the build and the tests need, installed when
# missing (as root) or named (otherwise). Sourced by scripts/build, demo, test.
SQ_DEBIAN_PACKAGES=(
  cmake make gcc g++ pkg-config python3
  libgmp-dev          # exact predicates (GMP rationals)
  libsuitesparse-dev  # CHOLMOD and UMFPACK sparse solvers
  libopenmesh-dev     # cross-check of our mesh readers (tests only)
  libcmocka-dev       # unit tests
  libdouble-conversion-dev # shortest exact decimals in OBJ output (core/adapter_double_conversion.cpp)
  libceres-dev        # nonlinear least squares for quad smoothing (stages/adapter_ceres.cpp)
  liblemon-dev        # LEMON network simplex: min-cost flow for integer T-mesh arc lengths (quantize/adapter_lemon.cpp)
  libcgal-dev         # CGAL Polygon Mesh Processing: the self-intersection test of remesh (stages/adapter_cgal.cpp)
  libosd-dev          # OpenSubdiv: Catmull-Clark patches and limit evaluation (stages/adapter_opensubdiv.cpp)
  libocct-data-exchange-dev       # OpenCASCADE STEP/IGES readers: CAD import check (tests only)
  libocct-modeling-algorithms-dev # OpenCASCADE BRepCheck_Analyzer (tests only)
  libocct-modeling-data-dev       # OpenCASCADE B-rep and B-spline geometry (tests only)
  libocct-foundation-dev          # OpenCASCADE kernel (tests only)
)

sq_missing_packages() {
  local p missing=()
  for p in "${SQ_DEBIAN_PACKAGES[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  echo "${missing[@]}"
}

sq_install_deps() {
  local missing
  missing=$(sq_missing_packages)
  [ -z "$missing" ] && return 0
  if [ "$(id -u)" = 0 ]; then
    echo "seamquad: installing Debian packages: $missing"
    export DEBIAN_FRONTEND=noninteractive
    apt-get update -qq || { echo "seamquad: apt-get update failed" >&2; return 1; }
    # shellcheck disable=SC2086
    apt-get install -y -qq --no-install-recommends $missing >/dev/null ||
      { echo "seamquad: apt-get install failed for: $missing" >&2; return 1; }
  else
    echo "seamquad: missing Debian packages; as root run:" >&2
    echo "  apt-get install $missing" >&2
    return 1
  fi
}
