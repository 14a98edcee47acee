#!/usr/bin/env bash
# stage.sh OUTDIR - make a run folder a self-contained static site: copy the viewer page
# (web/ next to this script) and the parts of CesiumJS it loads into OUTDIR/viewer/.
# OUTDIR/viewer/index.html then reads ../mission.czml and ../summary.json; serve OUTDIR with
# any static HTTP server. Cost: about 14 MB (Cesium.js 5.8 MB, Assets 4.7 MB, Workers 1.3 MB,
# ThirdParty 1.1 MB, Widgets 0.7 MB); the ES-module and CommonJS bundles are left out.
# Works from where it lies, in one of two layouts:
#   source tree viewer/:        web/, install.sh, node_modules/cesium/Build/Cesium (npm ci)
#   share/lvsim/viewer/ of an installation or of the build tree: web/, cesium/ (copied there
#                               by cmake/lv_data_files.cmake when node_modules had CesiumJS)
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
me="$here/stage.sh"
[ $# -eq 1 ] || { echo "usage: $me OUTDIR" >&2; exit 2; }
out="$1"
[ -d "$out" ] || { echo "$me: '$out' is not a directory" >&2; exit 2; }
[ -f "$out/summary.json" ] || echo "$me: warning: '$out' has no summary.json" >&2
[ -f "$out/mission.czml" ] || echo "$me: warning: '$out' has no mission.czml (run lvsim export)" >&2
if [ -f "$here/cesium/Cesium.js" ]; then          # installed (or build tree) layout
  src="$here/cesium"
  pkg="$here/cesium/package.json"
elif [ -x "$here/install.sh" ]; then              # source tree: npm packages on demand
  "$here/install.sh"
  src="$here/node_modules/cesium/Build/Cesium"
  pkg="$here/node_modules/cesium/package.json"
else
  echo "$me: CesiumJS is missing: no $here/cesium/Cesium.js. It is copied there from the" \
       "source tree's viewer/node_modules when building or installing lvsim: run 'make viewer'" \
       "in the source tree, then build (or install) again" >&2
  exit 1
fi
dst="$out/viewer"
rm -rf "$dst"
mkdir -p "$dst/cesium"
cp "$here/web/index.html" "$here/web/app.js" "$here/web/style.css" "$dst/"
cp -R "$src/Cesium.js" "$src/Assets" "$src/Workers" "$src/ThirdParty" "$src/Widgets" "$dst/cesium/"
cesium_version=$(sed -n 's/^ *"version": *"\([^"]*\)".*/\1/p' "$pkg" | head -1)
printf 'lvsim viewer, CesiumJS %s\n' "$cesium_version" > "$dst/VERSION"
echo "$dst/index.html"
