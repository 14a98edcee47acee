#!/usr/bin/env bash
# Install the viewer's npm packages (cesium; playwright-core for the browser test) from
# viewer/package-lock.json with `npm ci`, only when node_modules is missing or older than
# the lock file. Needs node and npm and the npm registry; nothing else is downloaded.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here"
stamp=node_modules/.package-lock.json     # written by npm at every install
if [ -f "$stamp" ] && [ -d node_modules/cesium/Build/Cesium ] && [ ! package-lock.json -nt "$stamp" ] \
   && [ ! package.json -nt "$stamp" ]; then
  exit 0
fi
command -v npm >/dev/null || { echo "viewer/install.sh: npm not found (install Node.js >= 20)" >&2; exit 1; }
echo "viewer/install.sh: npm ci in $here"
npm ci --no-audit --no-fund --loglevel=error
touch "$stamp"
