# Monte Carlo campaigns (liblvsim_post; SQLite): the worker and the threaded driver, the
# database, the statistics, the figures and report. On top of liblvsim's public API
# (lv_mission.h, lv_dispersion.h).
list(APPEND LV_POST_SOURCES
  src/campaign/campaign.c
  src/campaign/store.c
  src/campaign/sqlite_dl.c
  src/campaign/stats.c
  src/campaign/mc_geom.c
  src/campaign/plot.c)
# its figures (PLplot) go into the figures' module lvsim_plot.so (src/post/plot.cmake)
list(APPEND LV_PLOT_MODULE_SOURCES src/campaign/mc_plot.c)
