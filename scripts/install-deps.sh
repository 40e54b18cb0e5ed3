#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Install what building and testing dynkit needs on Debian/Ubuntu (as root, or through sudo).
# The core library needs only a C11 compiler and libm; the rest is for the CLI's tests:
# cmocka, and for the checks of the HTML pages in a real browser Chromium, node and npm
# (Debian's packages, each only when missing) and playwright-core from npm (npm ci in
# tests/browser, only when node_modules does not match package-lock.json). The benchmarks'
# peers (bench/: GSL, Boost.Odeint, SUNDIALS ARKODE and CVODE) come from Debian's packages too,
# so that CI builds and runs the peer benchmarks; without them everything else still builds.
# Safe to rerun.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(build-essential cmake pkg-config libcmocka-dev clang chromium)
packages+=(libgsl-dev libboost-dev libsundials-dev) # bench/ peers
packages+=(libtcc-dev tcc) # src/jit: models compiled in process by libtcc (optional)
packages+=(liblapack-dev) # backends/lapack: LAPACK's band LU for the stiff methods (optional)
packages+=(libsuitesparse-dev) # backends/klu: KLU, the sparse LU of the stiff methods (optional)
packages+=(libopenmpi-dev openmpi-bin) # backends/mpi: sweeps over MPI ranks (optional)
# .mat output with matio (optional); the data-file tests load every format with NumPy, SciPy
# and Octave (tests/test_formats.c; octave installs in about 30 s); SymPy checks the derived
# equations of mechanisms (tests/mbs/sympy_check.py)
packages+=(libmatio-dev python3-numpy python3-scipy python3-sympy octave)
# the Python package (bindings/python) and its tests (tests/python, pytest); pandas for
# the DataFrames of Run.to_dataframe and Table.to_dataframe
packages+=(python3-dev python3-pytest python3-pandas)
packages+=(liboctave-dev) # mkoctfile: the MEX functions for Octave (bindings/matlab)
packages+=(man-db) # tests/test_manpage.c renders docs/dynkit.1
packages+=(xppaut) # tests/xppaut: .ode files run by XPPAUT itself and compared
packages+=(auto-07p gfortran) # tests/continuation, bench/colloc_auto.py: AUTO-07p as the oracle
packages+=(lld wasi-libc libclang-rt-14-dev-wasm32) # backends/wasm: live pages (clang for wasm32-wasi)
packages+=(zlib1g-dev) # live pages: the module compressed (cli/pages/zlib_write.c; optional)
packages+=(libclang-rt-dev) # fuzz/: libFuzzer and the sanitizers' runtime for clang (CI)
# node and npm may come from elsewhere (e.g. a newer nodejs that bundles npm): keep those
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
missing=()
for p in "${packages[@]}"; do
  [[ "$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null)" == *"install ok installed"* ]] ||
    missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: the system packages are installed"
else
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  echo "install-deps: installing ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# playwright-core for tests/browser, at the version of package-lock.json
browser=tests/browser
locked=$(node -e "console.log(require('./$browser/package-lock.json').packages['node_modules/playwright-core'].version)")
installed=$(node -e "try { console.log(require('./$browser/node_modules/playwright-core/package.json').version) } catch (e) { console.log('none') }")
if [ "$locked" = "$installed" ]; then
  echo "install-deps: playwright-core $installed is installed in $browser"
else
  echo "install-deps: npm ci in $browser (playwright-core $locked)"
  (cd "$browser" && npm ci --no-audit --no-fund)
fi
