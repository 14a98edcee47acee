# 3-DoF model through lv_simulate.
lv_add_unit_test(test_dof3 unit/test_dof3.c)
