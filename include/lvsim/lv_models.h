/* lv_models.h - built-in reference models with closed-form solutions.
 *
 * They serve as examples of lv_model_def, as the problems of the integrator's
 * tests and benchmarks, and as `lvsim simulate MODEL` targets. Each is a small
 * pure function of its state; discrete modes live in lv_basic_inst.
 *
 *   vertical_ascent  1-D rocket in uniform gravity: constant thrust and mass flow
 *                    until burnout (state event m = m_final), coast, apogee, impact
 *   free_fall        1-D fall in uniform gravity, stops at ground impact
 *                    (both: domain h >= 0, so a start below the ground - h or h0 < 0 - is
 *                    LV_ERR_INPUT naming h, its value and the bound, not a missed impact)
 *   oscillator       harmonic oscillator x'' = -omega^2 x
 *   kepler           two-body orbit r'' = -mu r/|r|^3, periapsis passages as events
 */
#ifndef LVSIM_LV_MODELS_H
#define LVSIM_LV_MODELS_H

#include "lvsim/lv_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Instance data of the built-in models: the discrete mode. */
typedef struct lv_basic_inst {
    int engine_on;   /* vertical_ascent: 1 while burning */
    const char *why; /* why the last start or init failed (a static text), or NULL */
} lv_basic_inst;

/* State indices. */
enum lv_ascent_x { LV_ASC_H, LV_ASC_V, LV_ASC_M, LV_ASC_N };
enum lv_ascent_ev { LV_ASC_EV_BURNOUT, LV_ASC_EV_APOGEE, LV_ASC_EV_IMPACT, LV_ASC_EV_N };
enum lv_kepler_x { LV_KEP_RX, LV_KEP_RY, LV_KEP_RZ, LV_KEP_VX, LV_KEP_VY, LV_KEP_VZ, LV_KEP_N };

LV_API extern const lv_model_def lv_model_vertical_ascent;
LV_API extern const lv_model_def lv_model_free_fall;
LV_API extern const lv_model_def lv_model_oscillator;
LV_API extern const lv_model_def lv_model_kepler;

/* Built-in model by name, or NULL. `list` (may be NULL) receives the NULL-terminated table. */
LV_API const lv_model_def *lv_models_find(const char *name);
LV_API const lv_model_def *const *lv_models_all(void);

#ifdef __cplusplus
}
#endif
#endif
