# Plots and the HTML report (PLplot, cairo drivers): post-processing after a run.
list(APPEND LV_POST_SOURCES
  src/post/plot_draw.c
  src/post/plot_html.c
  src/post/plot_keys.c
  src/post/plot.c)
