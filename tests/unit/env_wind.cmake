# Table atmosphere, wind tables and profiles (src/env/atmosphere_table.c, wind.c, profile.c,
# atmosphere_profile.c).
lv_add_unit_test(test_wind_atmo unit/test_wind_atmo.c)
lv_add_unit_test(test_profile unit/test_profile.c)
lv_add_unit_test(test_turbulence unit/test_turbulence.c)
lv_add_unit_test(test_perturbation unit/test_perturbation.c)
