# Optimal control over a mission's phase tree (lv_ocp.h): direct multiple shooting, the
# finite-difference Jacobian in column groups, IPOPT (loaded on first use), the optimal mission.
list(APPEND LV_SOURCES
  src/optimal/ocp.c
  src/optimal/ocp_write.c
  src/optimal/ipopt_dl.c)
