#!/usr/bin/env bash
# test_install.sh SOURCE_DIR [BUILD_DIR [CMAKE]] - `cmake --install` gives a working prefix
# that needs neither the source nor the build tree:
#   1. copy the source tree (the files git lists, without build trees or node_modules; a
#      stand-in CesiumJS build in viewer/node_modules so that the viewer is installed too);
#   2. configure it (tests, benchmarks and examples off; CMAKE_INSTALL_PREFIX elsewhere, so
#      that data must be found next to the library), build, install into a prefix;
#   3. delete the copied source and build trees and move the prefix;
#   4. build tests/install/consumer with find_package(lvsim) and run it on mission.yaml
#      (gravity sh:4: the EGM2008 file is looked up at run time); run the installed
#      `lvsim check`, `lvsim run --no-plots` and `lvsim view --stage-only`, and one lookup
#      that fails, for its message;
#   5. no installed file contains the temporary or the real source or build path, and the
#      private dependencies (SUNDIALS, matio, HDF5, libyaml, NLopt, cJSON, PLplot) do not reach
#      the consumer;
#   6. the Python package: the installed one (lib/python3/dist-packages/lvsim, in the moved
#      prefix) imports with Debian's python3, loads the prefix's liblvsim and runs the mission;
#      a pip install of the real build tree's build/python (--target, and into a venv with
#      --system-site-packages; no index) does the same with the build tree's library.
# Prints "N passed, M failed" and the time of each step.
set -uo pipefail
src="$(cd "$1" && pwd)"
real_build="${2:-}"
cmake="${3:-cmake}"
jobs="${LV_INSTALL_JOBS:-2}"
here="$src/tests/install"
unset LVSIM_DATA
tmp="$(mktemp -d "${TMPDIR:-/tmp}/lvsim-install.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
copy="$tmp/source" build="$tmp/build" prefix="$tmp/prefix" moved="$tmp/moved"
pass=0 fails=0 t0=$SECONDS

ok() { pass=$((pass + 1)); }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
step() { echo "[$((SECONDS - t0)) s] $*"; }
finish() { step "done"; echo "$pass passed, $fails failed"; [ "$fails" -eq 0 ]; exit; }
# run LOG command...: runs quietly, shows the log's end when it fails
run() {
  local log="$tmp/$1.log"; shift
  if "$@" > "$log" 2>&1; then return 0; fi
  echo "command failed: $*"; tail -n 30 "$log"; return 1
}
# expect CODE PATTERN -- command...: exit code and an extended regex on stdout + stderr
expect() {
  local code="$1" pat="$2"; shift 3
  local out rc
  out=$("$@" 2>&1); rc=$?
  if [ "$rc" -ne "$code" ] || ! grep -qE -- "$pat" <<<"$out"; then
    fail "$* -> exit $rc (want $code), output:"; echo "$out" | head -n 8
    echo "      expected pattern: $pat"
  else
    ok
  fi
}

step "copy $src -> $copy"
mkdir -p "$copy"
if git -C "$src" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  # tracked and new files, as git sees them (.gitignore drops build*/ and node_modules/)
  git -C "$src" ls-files -z --cached --others --exclude-standard \
    | tar -C "$src" --null --ignore-failed-read -T - -cf - 2> /dev/null | tar -C "$copy" -xf -
else
  tar -C "$src" --exclude='./build*' --exclude=node_modules --exclude=.git -cf - . \
    | tar -C "$copy" -xf -
fi
[ -f "$copy/CMakeLists.txt" ] && [ -f "$copy/data/gravity/egm2008_n20.gfc" ] && ok \
  || { fail "source copy incomplete"; finish; }
fake="$copy/viewer/node_modules/cesium"
mkdir -p "$fake/Build/Cesium/"{Assets,Workers,ThirdParty,Widgets}
for d in Assets Workers ThirdParty Widgets; do echo "$d" > "$fake/Build/Cesium/$d/stand-in.txt"; done
echo '// stand-in for the CesiumJS build' > "$fake/Build/Cesium/Cesium.js"
printf '{\n  "name": "cesium",\n  "version": "0.0.7-install-test"\n}\n' > "$fake/package.json"
echo 'Apache License 2.0 (stand-in)' > "$fake/LICENSE.md"

step "configure and build (-j$jobs)"
run configure "$cmake" -S "$copy" -B "$build" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$tmp/configured-prefix" \
    -DLV_BUILD_TESTS=OFF -DLV_BUILD_BENCH=OFF -DLV_BUILD_EXAMPLES=OFF && ok || { fail configure; finish; }
run build "$cmake" --build "$build" -j "$jobs" && ok || { fail build; finish; }
step "install into $prefix"
run install "$cmake" --install "$build" --prefix "$prefix" && ok || { fail install; finish; }
echo "install tree:"; (cd "$prefix" && find . -maxdepth 3 | sort | sed 's/^/  /')

step "delete the source copy and the build tree; move the prefix to $moved"
rm -rf "$copy" "$build"
mv "$prefix" "$moved"
for f in bin/lvsim lib/liblvsim.so.0 include/lvsim/lvsim.h include/lvsim/lv_data.h \
         lib/cmake/lvsim/lvsimConfig.cmake lib/cmake/lvsim/lvsimConfigVersion.cmake \
         lib/cmake/lvsim/lvsimTargets.cmake share/lvsim/gravity/egm2008_n20.gfc \
         share/lvsim/viewer/web/index.html share/lvsim/viewer/cesium/Cesium.js \
         share/lvsim/viewer/cesium/LICENSE.md; do
  [ -f "$moved/$f" ] && ok || fail "not installed: $f"
done
[ -x "$moved/share/lvsim/viewer/stage.sh" ] && ok || fail "share/lvsim/viewer/stage.sh not executable"
[ -x "$moved/bin/lvsim" ] && ok || fail "bin/lvsim not executable"
readelf -d "$moved/bin/lvsim" | grep -qE 'R(UN)?PATH.*\[\$ORIGIN/\.\./lib\]' && ok \
  || fail "bin/lvsim: RUNPATH is not \$ORIGIN/../lib: $(readelf -d "$moved/bin/lvsim" | grep PATH)"

step "consumer: find_package(lvsim), build, run"
mission="$here/mission.yaml"
run consumer-configure "$cmake" -S "$here/consumer" -B "$tmp/consumer" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$moved" && ok || fail "consumer: configure"
run consumer-build "$cmake" --build "$tmp/consumer" && ok || fail "consumer: build"
gfc="$moved/share/lvsim/gravity/egm2008_n20.gfc"
expect 0 "^gravity file: $gfc\$" -- "$tmp/consumer/consumer" "$mission"
expect 0 "^install-check: 2 phases, final altitude [0-9]+\.[0-9] km\$" -- "$tmp/consumer/consumer" "$mission"
# private dependencies stay private: neither the consumer nor the package names them
deps='sundials|matio|hdf5|yaml|nlopt|cjson|plplot'
if readelf -d "$tmp/consumer/consumer" | grep NEEDED | grep -qiE "$deps"; then
  fail "consumer links a private dependency: $(readelf -d "$tmp/consumer/consumer" | grep NEEDED)"
else ok; fi
# (the post-processing library's one interface dependency is the core: lvsim::lvsim)
leak='SUNDIALS::|PkgConfig::|Threads::|lv_deps|lv_post_deps|find_dependency'
links=$(grep -hE 'INTERFACE_LINK_LIBRARIES' "$moved"/lib/cmake/lvsim/*.cmake | grep -vE '"lvsim::lvsim"' || true)
if grep -qE "$leak" "$moved"/lib/cmake/lvsim/*.cmake || [ -n "$links" ]; then
  fail "the CMake package passes on dependencies: $(grep -hE "$leak" "$moved"/lib/cmake/lvsim/*.cmake) $links"
else ok; fi

step "installed CLI"
lvsim="$moved/bin/lvsim"
expect 0 "is valid: 2 phases" -- "$lvsim" check "$mission"
expect 0 "upper-burn .* done" -- "$lvsim" run "$mission" -o "$tmp/run" --no-plots
[ -f "$tmp/run/summary.json" ] && ok || fail "lvsim run: no summary.json"
# the figures' module is found next to the installed (and moved) liblvsim_post: lib/lvsim/
expect 0 "plots in $tmp/run/plots/" -- "$lvsim" plot "$tmp/run"
[ -f "$tmp/run/plots/altitude.png" ] && [ -f "$moved/lib/lvsim/lvsim_plot.so" ] && ok \
  || fail "lvsim plot: no figure, or no lib/lvsim/lvsim_plot.so in the prefix"
expect 0 "viewer staged in $tmp/run/viewer/" -- "$lvsim" view "$tmp/run" --stage-only
# the FMU binary is found next to the installed (and moved) liblvsim_post too: lib/lvsim/
expect 0 "wrote $tmp/ascent.fmu: FMI 2.0" -- "$lvsim" fmu "$mission" --phase ascent -o "$tmp/ascent.fmu"
# the listing captured first: `unzip -l | grep -q` under pipefail fails at random when grep
# exits at its first match and unzip dies of SIGPIPE writing the rest (exit 141)
fmu_listing="$(unzip -l "$tmp/ascent.fmu" 2> /dev/null)"
grep -q "binaries/linux64/.*\.so" <<< "$fmu_listing" && ok \
  || fail "lvsim fmu: no binary in the archive from the prefix"
grep -qx "lvsim viewer, CesiumJS 0.0.7-install-test" "$tmp/run/viewer/VERSION" 2> /dev/null \
  && [ -f "$tmp/run/viewer/index.html" ] && ok || fail "lvsim view: viewer not staged from the prefix"
# nothing found: the message lists each folder searched
mv "$moved/share" "$moved/share.off"
expect 2 "gravity/egm2008_n20.gfc: lvsim data file not found \(LVSIM_DATA not set\); searched $moved/share/lvsim \(next to the library\), $tmp/configured-prefix/share/lvsim \(install prefix\)" \
  -- "$lvsim" gravity 0 0 0 --model sh
mv "$moved/share.off" "$moved/share"
expect 0 "^[-0-9.e]+ [-0-9.e]+ 9\.814[0-9]* 9\.814" -- env LVSIM_DATA="$moved/share/lvsim" "$lvsim" gravity 0 0 0 --model sh

step "Python package: installed, and pip-installed from the build tree"
py=/usr/bin/python3
pycheck='import lvsim, sys
m = lvsim.Mission(sys.argv[1]); r = m.run()
print("lvsim", lvsim.__version__, "from", lvsim.library_path)
print("python-check: %d phases, final altitude %.1f km" % (len(m.phases), r.final(len(m.phases) - 1, "h") / 1e3))'
expect 0 "^lvsim [0-9.]+ from $moved/lib/liblvsim\.so\.0" -- env -u LVSIM_LIBRARY_DIR PYTHONDONTWRITEBYTECODE=1 \
  PYTHONPATH="$moved/lib/python3/dist-packages" "$py" -c "$pycheck" "$mission"
expect 0 "^python-check: 2 phases, final altitude [0-9]+\.[0-9] km\$" -- env PYTHONDONTWRITEBYTECODE=1 \
  PYTHONPATH="$moved/lib/python3/dist-packages" "$py" -c "$pycheck" "$mission"
if [ -n "$real_build" ] && [ -f "$real_build/python/pyproject.toml" ]; then
  rb="$(cd "$real_build" && pwd)"
  run pip-target "$py" -m pip install --no-build-isolation --no-index --no-cache-dir --quiet \
      --target "$tmp/pip" "$rb/python" && ok || fail "pip install --target"
  expect 0 "^lvsim [0-9.]+ from $rb/lib/liblvsim\.so\.0" -- env PYTHONDONTWRITEBYTECODE=1 \
    PYTHONPATH="$tmp/pip" "$py" -c "$pycheck" "$mission"
  run venv "$py" -m venv --system-site-packages "$tmp/venv" && \
    run pip-venv "$tmp/venv/bin/pip" install --no-build-isolation --no-index --no-cache-dir --quiet \
      "$rb/python" && ok || fail "pip install into a venv"
  expect 0 "^python-check: 2 phases" -- env PYTHONDONTWRITEBYTECODE=1 "$tmp/venv/bin/python" \
    -c "$pycheck" "$mission"
fi

step "no installed file contains a source or build path"
paths=("$copy" "$build" "$src")
[ -n "$real_build" ] && paths+=("$(cd "$real_build" && pwd)")
while IFS= read -r -d '' f; do
  for p in "${paths[@]}"; do
    n=$(grep -caF -- "$p" "$f")
    [ "$n" -eq 0 ] && ok || fail "${f#"$moved"/} contains '$p' ($n times)"
  done
done < <(find "$moved" -type f \( -path '*/bin/*' -o -path '*/lib/*' \) -print0)
finish
