# Targeting and optimisation over a mission's phase tree (lv_target.h): the problem and its
# evaluations with finite-difference sensitivities, Levenberg-Marquardt, NLopt's SLSQP and
# COBYLA, the converged mission file.
list(APPEND LV_SOURCES
  src/target/target.c
  src/target/newton.c
  src/target/optimize.c
  src/target/nlopt_dl.c
  src/target/write.c)
