lv_add_unit_test(test_simulate unit/test_simulate.c)
lv_add_unit_test(test_output unit/test_output.c)
