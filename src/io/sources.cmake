list(APPEND LV_SOURCES
  src/io/sink.c
  src/io/result_memory.c
  src/io/result_csv.c
  src/io/numfmt.cc
  src/io/numparse.cc
  src/io/result_mat.c
  src/io/result_formats.c
  src/io/matio_dl.c
  src/io/hdf5_dl.c
  src/io/table_load.c
  src/io/atomic.c
  src/io/readfile.c)
list(APPEND LV_DL_SOURCES src/io/nettle_dl.c)
