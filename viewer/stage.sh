#!/usr/bin/env bash
# stage.sh OUTDIR - make a run folder a self-contained static site: copy the viewer page
# (viewer/web) and the parts of CesiumJS it loads into OUTDIR/viewer/. OUTDIR/viewer/index.html
# then reads ../mission.czml and ../summary.json; serve OUTDIR with any static HTTP server.
# Cost: about 14 MB (Cesium.js 5.8 MB, Assets 4.7 MB, Workers 1.3 MB, ThirdParty 1.1 MB,
# Widgets 0.7 MB); the ES-module and CommonJS bundles (index.js, index.cjs) are left out.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
[ $# -eq 1 ] || { echo "usage: viewer/stage.sh OUTDIR" >&2; exit 2; }
out="$1"
[ -d "$out" ] || { echo "viewer/stage.sh: '$out' is not a directory" >&2; exit 2; }
[ -f "$out/summary.json" ] || echo "viewer/stage.sh: warning: '$out' has no summary.json" >&2
[ -f "$out/mission.czml" ] || echo "viewer/stage.sh: warning: '$out' has no mission.czml (run lvsim export)" >&2
"$here/install.sh"
src="$here/node_modules/cesium/Build/Cesium"
dst="$out/viewer"
rm -rf "$dst"
mkdir -p "$dst/cesium"
cp "$here/web/index.html" "$here/web/app.js" "$here/web/style.css" "$dst/"
cp -R "$src/Cesium.js" "$src/Assets" "$src/Workers" "$src/ThirdParty" "$src/Widgets" "$dst/cesium/"
cesium_version=$(sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' "$here/node_modules/cesium/package.json" | head -1)
printf 'lvsim viewer, CesiumJS %s\n' "$cesium_version" > "$dst/VERSION"
echo "$dst/index.html"
