include(src/env/atmosphere.cmake OPTIONAL)
include(src/env/planet.cmake OPTIONAL)
