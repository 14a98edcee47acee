# Unit tests of src/core.
lv_add_unit_test(test_table unit/test_table.c)
target_compile_definitions(test_table PRIVATE
  LV_TABLE_DATA_DIR="${PROJECT_SOURCE_DIR}/tests/data/tables")
