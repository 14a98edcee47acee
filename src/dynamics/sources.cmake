list(APPEND LV_SOURCES
  src/dynamics/flight.c
  src/dynamics/flight_ends.c
  src/dynamics/guidance.c
  src/dynamics/dof3.c
  src/dynamics/dof6.c
  src/dynamics/runway.c
  src/dynamics/orbit.c)
