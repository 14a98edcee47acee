lv_add_unit_test(test_erk unit/test_erk.c)
