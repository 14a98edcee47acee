/* atmosphere_us76_gen.c - build-time generator of the US76 upper-atmosphere table
 * (lv_us76_upper_1976): runs lv_us76_upper_build with the default step and node spacing and
 * prints the result as C source, every coefficient as a hexadecimal floating-point constant
 * (exact). CMake runs it while building lvsim (src/env/atmosphere.cmake); it is not part of
 * the library. Usage: lvsim_us76_gen OUTPUT.c */
#include <stdio.h>

#include "env/atmosphere.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTPUT.c\n", argv[0]);
        return 2;
    }
    lv_us76_upper up;
    lv_err err;
    if (lv_us76_upper_build(&up, LV_US76_UPPER_H, LV_US76_UPPER_NODE_DZ, &err) != LV_OK) {
        fprintf(stderr, "%s: %s\n", argv[0], err.msg);
        return 1;
    }
    FILE *f = fopen(argv[1], "w");
    if (f == NULL) {
        perror(argv[1]);
        lv_us76_upper_release(&up);
        return 1;
    }
    fprintf(f, "/* us76_upper_table.c - generated at build time by src/env/atmosphere_us76_gen.c "
               "(lv_us76_upper_build,\n * h = %g m, nodes every %g m): the US76 table from 86 km "
               "to 1000 km. Do not edit. */\n",
            LV_US76_UPPER_H, LV_US76_UPPER_NODE_DZ);
    fprintf(f, "#include \"env/atmosphere.h\"\n\n");
    fprintf(f, "static const double coef[%zu] = {\n", 8 * up.n);
    for (size_t i = 0; i < 8 * up.n; i++)
        fprintf(f, "%s%a,%s", i % 4 == 0 ? "    " : " ", up.c[i], i % 4 == 3 ? "\n" : "");
    fprintf(f, "};\n\nconst lv_us76_upper lv_us76_upper_1976 = {%a, %a, %zu, coef, 0};\n", up.z0,
            up.dz, up.n);
    lv_us76_upper_release(&up);
    if (fclose(f) != 0) {
        perror(argv[1]);
        return 1;
    }
    return 0;
}
