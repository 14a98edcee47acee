# Trajectory exports (CZML, KML, CCSDS OEM) from a results folder: docs/exports.md.
list(APPEND LV_SOURCES
  src/io/export.c
  src/io/export_czml.c
  src/io/export_kml.c
  src/io/export_oem.c)
