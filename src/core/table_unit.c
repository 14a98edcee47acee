/* table_unit.c - a table column's unit against the one lvsim reads it in (table_unit.h). */
#include "core/table_unit.h"

#include <string.h>

#include "core/status.h"

static int dimensionless(const char *u)
{
    return u[0] == '\0' || strcmp(u, "1") == 0 || strcmp(u, "-") == 0;
}

int lv_unit_matches(const char *given, const char *si)
{
    static const char *const same[][2] = {{"kg/m3", "kg/m^3"}, {"m/s2", "m/s^2"},
                                          {"m2", "m^2"}};
    if (given == NULL || given[0] == '\0' || strcmp(given, si) == 0)
        return 1;
    if (dimensionless(si))
        return dimensionless(given);
    for (size_t i = 0; i < sizeof same / sizeof same[0]; i++)
        if ((strcmp(given, same[i][0]) == 0 || strcmp(given, same[i][1]) == 0) &&
            (strcmp(si, same[i][0]) == 0 || strcmp(si, same[i][1]) == 0))
            return 1;
    return 0;
}

lv_status lv_table_expect_unit(const lv_table *t, int is_axis, size_t k, const char *si,
                               const char *what, lv_err *err)
{
    const char *u = is_axis ? lv_table_axis_unit(t, k) : lv_table_out_unit(t, k);
    if (lv_unit_matches(u, si))
        return LV_OK;
    return lv_fail(err, LV_ERR_INPUT, "%s%stable '%s': %s '%s' is in [%s]; lvsim reads it in %s "
                   "(write [%s] or no unit: no units are converted)", what ? what : "",
                   what ? ": " : "", lv_table_name(t), is_axis ? "axis" : "column",
                   is_axis ? lv_table_axis_name(t, k) : lv_table_out_name(t, k), u,
                   dimensionless(si) ? "1 (dimensionless)" : si,
                   dimensionless(si) ? "1" : si);
}
