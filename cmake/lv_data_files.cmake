# lv_data_files.cmake - copies lvsim's run-time data into a share/lvsim folder (LV_DST):
# data/ (gravity coefficients) and the 3-D viewer: viewer/stage.sh, viewer/web/ and, when the
# npm packages are there (make viewer), the parts of CesiumJS that stage.sh copies into a
# results folder, as viewer/cesium/. One list for the build tree and for an installation:
#   build time:   cmake -DLV_SRC=<source> -DLV_DST=<build>/share/lvsim -P lv_data_files.cmake
#   install time: include()d by install(CODE) with LV_MODE=INSTALL (cmake/lv_install.cmake)
# COPY and INSTALL both skip files whose copy has the same time stamp.
if(NOT LV_SRC OR NOT LV_DST)
  message(FATAL_ERROR "lv_data_files.cmake: set LV_SRC (source tree) and LV_DST (share/lvsim)")
endif()
if(NOT LV_MODE)
  set(LV_MODE COPY)
endif()

file(${LV_MODE} "${LV_SRC}/data/" DESTINATION "${LV_DST}" USE_SOURCE_PERMISSIONS)
file(${LV_MODE} "${LV_SRC}/viewer/stage.sh" "${LV_SRC}/viewer/web"
     DESTINATION "${LV_DST}/viewer" USE_SOURCE_PERMISSIONS)

set(_lv_cesium "${LV_SRC}/viewer/node_modules/cesium")
if(EXISTS "${_lv_cesium}/Build/Cesium/Cesium.js")
  # what stage.sh copies (~14 MB), the version (package.json) and the licence
  file(${LV_MODE}
       "${_lv_cesium}/Build/Cesium/Cesium.js" "${_lv_cesium}/Build/Cesium/Assets"
       "${_lv_cesium}/Build/Cesium/Workers" "${_lv_cesium}/Build/Cesium/ThirdParty"
       "${_lv_cesium}/Build/Cesium/Widgets" "${_lv_cesium}/package.json"
       "${_lv_cesium}/LICENSE.md"
       DESTINATION "${LV_DST}/viewer/cesium" USE_SOURCE_PERMISSIONS)
elseif(LV_MODE STREQUAL "INSTALL")
  message(STATUS "lvsim: viewer/node_modules/cesium not found: the viewer is installed without "
                 "CesiumJS (run `make viewer` in the source tree, then install again)")
endif()
