# Unit tests of src/core.
lv_add_unit_test(test_table unit/test_table.c)
target_compile_definitions(test_table PRIVATE
  LV_TABLE_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data/tables")
target_link_libraries(test_table PRIVATE PkgConfig::MATIO PkgConfig::HDF5) # writes .mat files itself
lv_add_unit_test(test_data unit/test_data.c)
target_compile_definitions(test_data PRIVATE LV_BINARY_DIR="${PROJECT_BINARY_DIR}"
  LV_TEST_INSTALL_DATADIR="${CMAKE_INSTALL_FULL_DATADIR}/lvsim")
# UTC with leap seconds (src/core/utc.c, ERFA) against the IERS list
lv_add_unit_test(test_utc unit/test_utc.c)
lv_add_unit_test(test_root unit/test_root.c)
