#!/usr/bin/env bash
# Install the Debian packages lvsim needs, only those missing. Idempotent.
#   scripts/install-deps.sh          build + test dependencies
# Uses sudo when not root. Debian 12 (bookworm) package names.
set -euo pipefail

pkgs=(
  cmake make gcc g++ pkg-config        # build (g++: the number formatter's shim, src/io/numfmt.cc)
  libdragonbox-dev                     # shortest round-trip digits of doubles (CSV files)
  libfast-float-dev                    # reading numbers back fast (results reader)
  libsundials-dev                      # CVODE, ARKODE (v6, SUNContext API)
  libmatio-dev                         # MAT v4/v5/v7 result and table files
  libhdf5-dev                          # MAT v7.3 tables libmatio cannot classify (src/io/table_load.c)
  libyaml-dev                          # mission files
  libcjson-dev                         # summary.json, exports
  liberfa-dev                          # UTC with leap seconds: the mission epoch, written times
  libnlopt-dev                         # lvsim target: SLSQP and COBYLA (src/target/optimize.c)
  coinor-libipopt-dev                  # lvsim optimize: IPOPT, the NLP solver (src/optimal/ocp.c)
  nettle-dev                           # SHA-256 in the results folder's manifest
  libzip-dev unzip                     # lvsim fmu: the FMU archive; its test unpacks it
  python3-scipy python3-numpy          # independent .mat reader in the tests; NumPy: the Python package
  python3-pandas python3-matplotlib    # the Python package's DataFrames; the example notebook's plots
  python3-pytest                       # the Python package's tests (ctest test_python)
  jupyter-nbconvert python3-ipykernel  # ctest test_notebook: examples/notebook.ipynb executed
  python3-setuptools python3-wheel python3-pip python3-venv  # pip install build/python (no index)
  libplplot-dev plplot-driver-cairo libplplot-data fonts-dejavu-core  # plots: PNG/SVG, coastlines
  libpng-dev                           # plots: PNG files written with fast settings
  clang libclang-rt-14-dev             # make fuzz: libFuzzer (ctest -L fuzz)
  chromium                             # headless browser for the viewer test (ctest test_viewer)
  python3                              # lvsim view serves with python3's http.server
  git ca-certificates                  # the fresh-clone test; npm's registry over https
  librandom123-dev                     # Philox counter-based generator: Monte Carlo dispersions
  libsqlite3-dev sqlite3               # Monte Carlo campaign database (and its dumps in the tests)
  libopenmpi-dev openmpi-bin           # mpirun -np K lvsim mc (optional in the build; tested in CI)
  time bc                              # bench/bench_mc.sh: a whole process's wall and CPU time
  procps                               # pgrep: test_outdir finds the drawing child process
)
# The viewer's npm packages (viewer/package.json, pinned for Debian 12's Node.js 18) need node
# and npm: Debian's nodejs and npm, unless a node and an npm are already installed (another
# distribution's node, such as NodeSource's, brings its own npm and conflicts with Debian's).
command -v node > /dev/null || pkgs+=(nodejs)
command -v npm > /dev/null || pkgs+=(npm)

missing=()
for p in "${pkgs[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
