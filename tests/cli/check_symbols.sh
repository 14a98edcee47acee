#!/usr/bin/env bash
# check_symbols.sh LIBLVSIM [LIBLVSIM_POST [LVSIM_PLOT_MODULE]] - the shared libraries' interfaces:
#  - every symbol each library exports starts with lv_ (STYLE.md: the libraries build with
#    -fvisibility=hidden and mark their API with LV_API);
#  - no symbol is exported by both (liblvsim_post's copies of core helpers stay hidden);
#  - the core library does not depend on PLplot (readelf -d: no libplplot in NEEDED), nor does
#    the post-processing library, which links liblvsim; lv_export_run and lv_plot_run come from
#    liblvsim_post, not from liblvsim; the figures' module links PLplot and sits in
#    <libdir>/lvsim/ next to liblvsim_post, which loads it when a figure is drawn.
set -euo pipefail
pass=0 fail=0
ok() { pass=$((pass + 1)); echo "ok: $*"; }
bad() { fail=$((fail + 1)); echo "FAILED: $*"; }

exported() { nm -D --defined-only "$1" | awk '$2 ~ /^[TDBRV]$/ {print $3}' | sort -u; }
needed() { readelf -d "$1" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p'; }

for lib in "$@"; do
  syms=$(exported "$lib")
  n=$(grep -c . <<<"$syms" || true)
  nonlv=$(grep -v '^lv_' <<<"$syms" | grep -v '^_' || true)
  if [ "$n" -gt 0 ] && [ -z "$nonlv" ]; then
    ok "$(basename "$lib"): $n exported symbols, all lv_*"
  else
    bad "$(basename "$lib"): exported symbols without the lv_ prefix (or none):"; echo "$nonlv"
  fi
done

core="$1"
if needed "$core" | grep -q '^libplplot'; then
  bad "$(basename "$core") needs PLplot: $(needed "$core" | tr '\n' ' ')"
else
  ok "$(basename "$core") does not link PLplot"
fi
if exported "$core" | grep -qx 'lv_export_run\|lv_plot_run'; then
  bad "$(basename "$core") exports post-processing functions"
else
  ok "$(basename "$core") exports no post-processing function"
fi

if [ $# -ge 2 ]; then
  post="$2"
  both=$(comm -12 <(exported "$core") <(exported "$post"))
  if [ -z "$both" ]; then
    ok "no symbol exported by both libraries"
  else
    bad "exported by both libraries:"; echo "$both"
  fi
  if ! needed "$post" | grep -q '^libplplot' && needed "$post" | grep -q '^liblvsim\.so'; then
    ok "$(basename "$post") links liblvsim, not PLplot (its figures' module does)"
  else
    bad "$(basename "$post") NEEDED: $(needed "$post" | tr '\n' ' ')"
  fi
  for f in lv_export_run lv_plot_run; do
    if exported "$post" | grep -qx "$f"; then
      ok "$(basename "$post") exports $f"
    else
      bad "$(basename "$post") does not export $f"
    fi
  done
fi

# The figures' module, <libdir>/lvsim/lvsim_plot.so next to liblvsim_post: it links PLplot and
# exports the two drawing entry points only, the run's and the campaign's figures (its copies of
# the helpers stay hidden).
if [ $# -ge 3 ]; then
  mod="$3"
  if needed "$mod" | grep -q '^libplplot' &&
     [ "$(exported "$mod" | tr '\n' ' ')" = "lv_mc_draw_figures lv_plot_draw_figures " ]; then
    ok "$(basename "$mod") links PLplot and exports lv_plot_draw_figures, lv_mc_draw_figures only"
  else
    bad "$(basename "$mod") exports: $(exported "$mod" | tr '\n' ' ') NEEDED: $(needed "$mod" | tr '\n' ' ')"
  fi
  if [ "$(dirname "$mod")" = "$(dirname "$post")/lvsim" ]; then
    ok "$(basename "$mod") is in $(dirname "$post")/lvsim, where liblvsim_post loads it"
  else
    bad "$mod is not in $(dirname "$post")/lvsim"
  fi
fi

echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
