lv_add_unit_test(test_atmosphere unit/test_atmosphere.c)
