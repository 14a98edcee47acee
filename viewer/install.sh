#!/usr/bin/env bash
# Install the viewer's npm packages (cesium; playwright-core for the browser test) from
# viewer/package-lock.json with `npm ci`, only when node_modules is missing or older than
# the lock file. Needs node and npm (Debian 12's Node.js 18 is enough: every package is pinned
# to a version whose `engines` accept it) and the npm registry; nothing else is downloaded.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"
stamp=node_modules/.package-lock.json     # written by npm at every install
if [ -f "$stamp" ] && [ -d node_modules/cesium/Build/Cesium ] && [ ! package-lock.json -nt "$stamp" ] \
   && [ ! package.json -nt "$stamp" ]; then
  exit 0
fi
command -v npm >/dev/null || { echo "viewer/install.sh: npm not found (Debian: apt-get install nodejs npm; scripts/install-deps.sh does)" >&2; exit 1; }
log="$here/npm-ci.log"
printf 'viewer/install.sh: npm ci in %s (CesiumJS, playwright-core; log %s) ... ' "$here" "$log"
# npm ci can hang after its downloads (npm/cli#4028; seen here once when two installs shared
# ~/.npm): each attempt is bounded (NPM_CI_TIMEOUT seconds, default 300; a normal install takes
# 15-40 s) and a failed or hung attempt is retried once, after `npm cache verify`.
limit="${NPM_CI_TIMEOUT:-300}"
attempt() { timeout --kill-after=10 "$limit" npm ci --no-audit --no-fund --loglevel=error >> "$log" 2>&1; }
: > "$log"
rc=0; attempt || rc=$?
if [ "$rc" -ne 0 ]; then
  [ "$rc" -eq 124 ] && why="no answer in $limit s" || why="exit $rc"
  printf '%s, retrying ... ' "$why"
  echo "--- viewer/install.sh: attempt 1 failed ($why); npm cache verify, attempt 2" >> "$log"
  timeout 120 npm cache verify >> "$log" 2>&1 || true
  if ! attempt; then
    echo "FAILED"; tail -n 30 "$log" >&2; exit 1
  fi
fi
echo "done"
touch "$stamp"
