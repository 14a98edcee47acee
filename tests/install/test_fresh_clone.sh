#!/usr/bin/env bash
# test_fresh_clone.sh SOURCE_DIR - the README's `make demo` in a clean copy of the sources
# (the files git lists, as a fresh clone has them: no build tree, no viewer/node_modules):
#   1. `make demo` runs from the copy: install-deps (nothing to install when the machine has
#      everything), the viewer's npm packages from viewer/package-lock.json, the build, the
#      demo; exit 0;
#   2. its output is short: one line for the build (the compiler's lines are in the log),
#      then the demo's own lines; the results folder is complete (manifest.json);
#   3. every shared library the built lvsim loads comes from a Debian package (dpkg -S) or
#      from the build tree: nothing from /usr/local, /opt or a home folder;
#   4. a build that fails prints its log's end and `make demo` fails.
# Bounded: about a minute (a build without tests, benchmarks and examples; npm ci from the
# npm cache or registry). Prints "N passed, M failed".
set -uo pipefail
src="$(cd "$1" && pwd)"
tmp="$(mktemp -d "${TMPDIR:-/tmp}/lvsim-fresh.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
copy="$tmp/lvsim" build="$tmp/lvsim/build"
pass=0 fails=0 t0=$SECONDS
ok() { pass=$((pass + 1)); }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
step() { echo "[$((SECONDS - t0)) s] $*"; }
finish() { step "done"; echo "$pass passed, $fails failed"; [ "$fails" -eq 0 ]; exit; }

step "copy the files git lists of $src -> $copy"
mkdir -p "$copy"
if git -C "$src" rev-parse --is-inside-work-tree > /dev/null 2>&1; then
  git -C "$src" ls-files -z --cached --others --exclude-standard \
    | tar -C "$src" --null --ignore-failed-read -T - -cf - 2> /dev/null | tar -C "$copy" -xf -
else
  tar -C "$src" --exclude='./build*' --exclude=node_modules --exclude=.git -cf - . \
    | tar -C "$copy" -xf -
fi
[ -f "$copy/Makefile" ] && [ ! -e "$copy/viewer/node_modules" ] && [ ! -e "$copy/build" ] && ok \
  || { fail "the copy is not a clean tree"; finish; }
if ! command -v npm > /dev/null; then
  echo "npm not found (scripts/install-deps.sh installs Debian's nodejs and npm)"; exit 77
fi

step "make demo"
flags="-DLV_BUILD_TESTS=OFF -DLV_BUILD_BENCH=OFF -DLV_BUILD_EXAMPLES=OFF"
out=$(cd "$copy" && make --no-print-directory demo BUILD="$build" JOBS="${LV_INSTALL_JOBS:-2}" \
      CMAKE_FLAGS="$flags" 2>&1); rc=$?
echo "$out" | sed 's/^/  | /'
[ "$rc" -eq 0 ] && ok || { fail "make demo: exit $rc"; finish; }
lines=$(wc -l <<<"$out")
[ "$lines" -le 50 ] && ok || fail "make demo printed $lines lines"
grep -qE "^building lvsim in $build/ \(log: $build/build.log\) \.\.\. done in [0-9]+ s$" <<<"$out" \
  && ok || fail "no one-line build message"
grep -qE "warning:|error:|Building C object|Linking C|^-- |\[ *[0-9]+%\]" <<<"$out" \
  && fail "compiler or CMake lines in the output" || ok
grep -q "Building C object" "$build/build.log" && ok || fail "the build log has no compiler lines"
grep -qE "^7 +approach +glide-back .* done$" <<<"$out" && grep -q "^results: $build/demo/" <<<"$out" && ok \
  || fail "the demo's own output is missing"
[ -f "$build/demo/manifest.json" ] && [ -f "$build/demo/viewer/VERSION" ] && ok \
  || fail "the demo's results folder or staged viewer is missing"

step "every shared library comes from Debian or the build tree"
libs=$(for bin in "$build/lvsim" "$build"/lib/liblvsim*.so.0; do ldd "$bin"; done \
       | awk '/=> \// {print $3}' | sort -u)
# dpkg knows a library by the path its package installed it under (/lib or /usr/lib: merged
# /usr); one dpkg -S for every candidate path, then each library needs one of its candidates
cands() { local r; r=$(readlink -f "$1"); printf '%s\n' "$1" "$r" "${r/#\/usr\/lib\//\/lib\/}" "${r/#\/lib\//\/usr\/lib\/}"; }
owned=$(while read -r lib; do [ -n "$lib" ] && cands "$lib"; done <<<"$libs" | sort -u \
        | xargs dpkg -S 2> /dev/null | sed 's/^.*: //' | sort -u)
while read -r lib; do
  [ -z "$lib" ] && continue
  case "$lib" in "$build"/*) ok; continue ;; esac
  if grep -qxF -f <(cands "$lib") <<<"$owned"; then ok
  else fail "lvsim loads $lib ($(readlink -f "$lib")), which no Debian package installed"; fi
done <<<"$libs"

step "a build that fails shows its log"
echo '#error lvsim-fresh-clone-test: broken on purpose' >> "$copy/src/core/status.c"
out=$(cd "$copy" && make --no-print-directory demo BUILD="$build" JOBS=2 CMAKE_FLAGS="$flags" 2>&1); rc=$?
[ "$rc" -ne 0 ] && grep -q "\.\.\. FAILED$" <<<"$out" && grep -q "broken on purpose" <<<"$out" && ok \
  || { fail "a failed build: exit $rc, output:"; echo "$out" | tail -5; }
finish
