include(${CMAKE_CURRENT_LIST_DIR}/env_atmosphere.cmake OPTIONAL)
include(${CMAKE_CURRENT_LIST_DIR}/env_planet.cmake OPTIONAL)
include(${CMAKE_CURRENT_LIST_DIR}/env_wind.cmake OPTIONAL)
