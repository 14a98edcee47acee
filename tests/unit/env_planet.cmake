# Planet, frames and gravity unit tests.
lv_add_unit_test(test_planet unit/test_planet.c)
lv_add_unit_test(test_gravity unit/test_gravity.c)
