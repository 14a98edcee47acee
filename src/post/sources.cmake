# Post-processing (liblvsim_post): reads a results folder back, never reruns anything. Exports
# (CZML, KML, CCSDS OEM), figures (PLplot, in the module lvsim_plot.so) and the HTML report.
# Links cJSON; the figures' module links PLplot; the core library links neither.
# The one reader of a results folder (summary.json, the CSV files), for all of them.
list(APPEND LV_POST_SOURCES src/post/results.c)
# Every JSON file written: cJSON's layout with exact (shortest round-trip) numbers.
list(APPEND LV_POST_SOURCES src/post/json_print.c)
# What a run leaves besides the phases' files: summary.json and the merged body trajectories.
list(APPEND LV_POST_SOURCES src/post/summary.c src/post/timeline.c)
# Run-atomic results folders: lock, staging folder replaced as a whole, manifest with SHA-256.
list(APPEND LV_POST_SOURCES src/post/outdir.c src/post/sha256.c)
include(src/post/export.cmake)
include(src/post/plot.cmake)
