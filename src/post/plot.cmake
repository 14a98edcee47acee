# Plots and the HTML report (PLplot, cairo drivers): post-processing after a run. liblvsim_post
# reads the results and writes the report (plot.c, plot_html.c); the figures (plot_draw.c:
# PLplot, libpng) are the module lvsim_plot.so, loaded when a figure is drawn (plot_load.c),
# so that PLplot is not loaded by a program that draws nothing. The static twin links them in
# (plot_link.c). CMakeLists.txt builds the module.
list(APPEND LV_POST_SOURCES
  src/post/plot_html.c
  src/post/plot_keys.c
  src/post/plot_series.c
  src/post/plot.c)
set(LV_PLOT_MODULE_SOURCES src/post/plot_draw.c)
