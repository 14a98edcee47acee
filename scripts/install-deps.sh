#!/usr/bin/env bash
# Install the Debian packages lvsim needs, only those missing. Idempotent.
#   scripts/install-deps.sh          build + test dependencies
# Uses sudo when not root. Debian 12 (bookworm) package names.
set -euo pipefail

pkgs=(
  cmake make gcc pkg-config            # build
  libsundials-dev                      # CVODE, ARKODE (v6, SUNContext API)
  libmatio-dev                         # MAT v4/v5/v7 result and table files
  libhdf5-dev                          # MAT v7.3 tables libmatio cannot classify (src/io/table_load.c)
  libyaml-dev                          # mission files
  libcjson-dev                         # summary.json, exports
  libnlopt-dev                         # lvsim target: SLSQP and COBYLA (src/target/optimize.c)
  python3-scipy python3-numpy          # independent .mat reader in the tests
  libplplot-dev plplot-driver-cairo libplplot-data fonts-dejavu-core  # plots: PNG/SVG, coastlines
  clang libclang-rt-14-dev             # make fuzz: libFuzzer (ctest fuzz_mission)
  chromium                             # headless browser for the viewer test (ctest test_viewer)
)

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
