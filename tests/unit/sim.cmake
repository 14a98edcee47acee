lv_add_unit_test(test_simulate unit/test_simulate.c)
