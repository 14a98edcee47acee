# Table atmosphere and wind tables (src/env/atmosphere_table.c, src/env/wind.c).
lv_add_unit_test(test_wind_atmo unit/test_wind_atmo.c)
