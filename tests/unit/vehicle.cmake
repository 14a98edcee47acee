# Vehicle data: engines and aerodynamic sets.
lv_add_unit_test(test_vehicle unit/test_vehicle.c)
