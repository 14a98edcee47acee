# Plots and the HTML report (PLplot, cairo drivers): post-processing after a run.
list(APPEND LV_SOURCES
  src/plot/plot_csv.c
  src/plot/plot_draw.c
  src/plot/plot_html.c
  src/plot/plot.c)
