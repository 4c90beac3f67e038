#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs imcol's build dependencies (Debian 12, as root) and builds into build/.
# SUNDIALS: Debian's libsundials is built without optimisation (its packaging's -DCMAKE_C_FLAGS=-fcommon
# replaces -O2), so the same Debian source package is fetched (apt-get source, from a deb-src entry for the
# archive this machine uses, kept in a sources file of its own) and built at -O3 with only CVODE and IDA into
# third_party_build/sundials-<version>/, shared libraries and static position-independent ones (the Python package
# links the static ones into its extension: setup.py); skipped when that exists with both, rebuilt when an older
# install lacks the static ones. Any failure there falls back to libsundials-dev. Non-root: no apt; a SUNDIALS
# already built in third_party_build/ is used if present.
# IMCOL_WERROR=ON in the environment builds imcol's own code with -Werror (CI does: a new compiler warning fails it);
# off by default, so that a newer compiler's new warning does not stop a user's build.
# pybind11-dev (with python3-dev) builds the Python module imcol into build/python/ (CMake option IMCOL_PYTHON);
# python3-pip, -setuptools, -wheel and -venv: `pip install --no-build-isolation .` in a venv (ctest python_install);
# python3-nbclient and python3-ipykernel run the example notebook in the tests.
# python3-vtk9: VTK's own reader checks the flow fields' files (ctest vtk_fields). Debian's paraview (pvpython, for the
# flow.py state beside flow.pvd) is left out: its python3-paraview conflicts with python3-vtk9 (and provides `vtk`).
# libopenmpi-dev and openmpi-bin: `mpirun -np N imcol sweep` over N ranks (CMake option IMCOL_MPI; docs/cluster.md);
# libnlopt-cxx-dev: NLopt, the bounded derivative-free local search of the calibration (required).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
DEPS=$ROOT/third_party_build

warn() { printf '\nsetup.sh: WARNING: %s\n\n' "$*" >&2; }

# Writes a deb-src entry for the Debian archive and suite that the machine's own sources use.
write_deb_src() {
  local codename uri="" keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
  [[ -n $codename ]] || return 1
  # deb822 stanzas (*.sources) with Types deb, the suite $codename and component main: first URI
  local f
  for f in /etc/apt/sources.list.d/*.sources; do
    [[ -f $f && -z $uri ]] || continue
    uri=$(awk -v s="$codename" '
      BEGIN { RS = ""; FS = "\n" }
      { t = u = su = c = 0
        for (i = 1; i <= NF; ++i) {
          if ($i ~ /^Types:/ && $i ~ /[ \t]deb([ \t]|$)/) t = 1
          if ($i ~ /^Suites:/ && (" " $i " ") ~ ("[ \t]" s "[ \t]")) su = 1
          if ($i ~ /^Components:/ && $i ~ /[ \t]main([ \t]|$)/) c = 1
          if ($i ~ /^URIs:/) { split($i, a, /[ \t]+/); u = a[2] }
        }
        if (t && su && c && u) { print u; exit } }' "$f")
  done
  # one-line format: deb [opts] URI codename components...
  if [[ -z $uri ]]; then
    uri=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
      sed -E 's/\[[^]]*\]//' | awk -v s="$codename" '$1 == "deb" && $3 == s && / main/ { print $2; exit }')
  fi
  [[ -n $uri ]] || uri=http://deb.debian.org/debian
  {
    echo "Types: deb-src"
    echo "URIs: $uri"
    echo "Suites: $codename"
    echo "Components: main"
    [[ -f $keyring ]] && echo "Signed-By: $keyring"
  } >"$1"
}

# Fetches Debian's SUNDIALS source package (the version of libsundials-dev) and installs an -O3 build
# of the modules imcol uses into $DEPS/sundials-<version>/install. Prints that prefix.
build_sundials() {
  local ver src work prefix
  ver=$(apt-cache show --no-all-versions libsundials-dev 2>/dev/null | awk '/^Version:/ { print $2; exit }')
  [[ $ver == 6.* ]] || { echo "no libsundials-dev 6.x candidate (got '${ver}')" >&2; return 1; }
  prefix=$DEPS/sundials-$ver/install
  if [[ -f $prefix/lib/cmake/sundials/SUNDIALSConfig.cmake && -f $prefix/lib/libsundials_cvode.a ]]; then
    echo "$prefix"; return 0
  fi
  work=$DEPS/sundials-$ver/work
  rm -rf "$work" "$prefix.tmp" && mkdir -p "$work/lists/partial"
  write_deb_src "$work/deb-src.sources"
  # own sources file and lists directory: the machine's apt state is left as it is
  local apt_opts=(-o Dir::Etc::SourceList="$work/deb-src.sources" -o Dir::Etc::SourceParts=/dev/null
                  -o Dir::State::Lists="$work/lists" -o APT::Sandbox::User=root)
  apt-get "${apt_opts[@]}" update -qq >&2
  (cd "$work" && apt-get "${apt_opts[@]}" source -qq "sundials=$ver" >&2)
  src=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'sundials-*' | head -1)
  [[ -n $src ]] || return 1
  # Debian passes -DCMAKE_C_FLAGS=-fcommon with no build type, i.e. no -O: here Release (-O3) keeps -fcommon
  cmake -S "$src" -B "$work/build" -G Ninja -Wno-dev \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS_RELEASE="-O3 -DNDEBUG" -DCMAKE_C_FLAGS=-fcommon \
    -DCMAKE_INSTALL_PREFIX="$prefix.tmp" -DCMAKE_INSTALL_LIBDIR=lib \
    -DBUILD_SHARED_LIBS=ON -DBUILD_STATIC_LIBS=ON -DCMAKE_POSITION_INDEPENDENT_CODE=ON \
    -DBUILD_CVODE=ON -DBUILD_IDA=ON -DBUILD_ARKODE=OFF -DBUILD_CVODES=OFF -DBUILD_IDAS=OFF -DBUILD_KINSOL=OFF \
    -DBUILD_NVECTOR_MANYVECTOR=OFF -DBUILD_FORTRAN_MODULE_INTERFACE=OFF -DBUILD_BENCHMARKS=OFF \
    -DEXAMPLES_ENABLE_C=OFF -DEXAMPLES_ENABLE_CXX=OFF -DEXAMPLES_INSTALL=OFF \
    -DENABLE_MPI=OFF -DENABLE_OPENMP=OFF -DENABLE_PTHREAD=OFF -DENABLE_LAPACK=OFF >&2
  cmake --build "$work/build" -j"$(nproc)" >&2
  cmake --install "$work/build" >/dev/null
  # the install dir is moved into place last: a half-built prefix is never taken for a finished one
  rm -rf "$prefix"  # an older install without the static libraries
  mv "$prefix.tmp" "$prefix"
  rm -rf "$work"
  echo "$prefix"
}

SUNDIALS_PREFIX=""
if [[ $(id -u) -eq 0 ]] && command -v apt-get >/dev/null; then
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends \
    cmake ninja-build g++ dpkg-dev libeigen3-dev libfftw3-dev libcli11-dev libtomlplusplus-dev \
    nlohmann-json3-dev libgtest-dev libbenchmark-dev libcerf-dev python3-matplotlib python3-meshio python3-vtk9 \
    pybind11-dev python3-dev python3-numpy python3-pytest python3-pip python3-setuptools python3-wheel python3-venv \
    python3-nbclient python3-ipykernel python3-nbformat \
    libopenmpi-dev openmpi-bin libnlopt-cxx-dev >/dev/null
  t0=$SECONDS
  mkdir -p "$DEPS"
  log=$DEPS/sundials-build.log
  set +e  # a failure anywhere in build_sundials ends only its subshell (-e is off inside `if` conditions)
  SUNDIALS_PREFIX=$(set -e; build_sundials 2>"$log")
  rc=$?
  set -e
  if [[ $rc -eq 0 && -n $SUNDIALS_PREFIX ]]; then
    echo "setup.sh: optimised SUNDIALS in $SUNDIALS_PREFIX ($((SECONDS - t0)) s; log $log)"
  else
    SUNDIALS_PREFIX=""
    tail -n 15 "$log" >&2 || true
    warn "building SUNDIALS from Debian's source package failed (log: $log); using Debian's libsundials-dev (unoptimised, slower)"
    apt-get install -y -qq --no-install-recommends libsundials-dev >/dev/null
  fi
else
  for p in "$DEPS"/sundials-*/install; do
    [[ -f $p/lib/cmake/sundials/SUNDIALSConfig.cmake ]] && SUNDIALS_PREFIX=$p
  done
  [[ -n $SUNDIALS_PREFIX ]] || warn "not root: using the installed SUNDIALS (run as root once to build an optimised one)"
fi
if [[ -n $SUNDIALS_PREFIX ]]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIMCOL_WERROR="${IMCOL_WERROR:-OFF}" -DSUNDIALS_DIR="$SUNDIALS_PREFIX/lib/cmake/sundials"
else
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DIMCOL_WERROR="${IMCOL_WERROR:-OFF}" -USUNDIALS_DIR
fi
cmake --build build -j"$(nproc)"
