# Trajectory exports (CZML, KML, CCSDS OEM) from a results folder: docs/exports.md.
list(APPEND LV_POST_SOURCES
  src/post/export.c
  src/post/export_czml.c
  src/post/export_glb.c
  src/post/export_kml.c
  src/post/export_oem.c)
