# 3-DoF model through lv_simulate.
lv_add_unit_test(test_dof3 unit/test_dof3.c)
# The runway model (take-off roll, landing roll-out) against closed forms of the ground roll,
# and the `runway` phase type in missions (parse errors, hand-offs to and from dof3).
lv_add_unit_test(test_runway unit/test_runway.c)
# The 6-DoF rigid body against conservation laws and closed forms (torque-free motion,
# precession, rate damping, quaternion norm, free fall equal to dof3's, thrust moments).
lv_add_unit_test(test_dof6 unit/test_dof6.c)
target_link_libraries(test_dof6 PRIVATE lvsim_post_static) # summary.json's transitions
# The 6-DoF model's switchable rigid-body terms (jet damping, inertia rate, the frame of the
# rate damping) against closed forms, and their mission keys.
lv_add_unit_test(test_dof6_terms unit/test_dof6_terms.c)
# The registered steering and throttle laws: each law's contract (and laws broken on purpose
# failing it), the C API that sets a law's keys by name, and the models' refusals.
lv_add_unit_test(test_laws unit/test_laws.c)
# The instantaneous impact point against a drag-free J2 propagation written in the test (RK4,
# halved steps, bisection): states along examples/kourou-leo's ascent, a booster arc, a
# sounding rocket, a polar arc, a hyperbola; no impact in orbit or escaping (NaN); the dof3 and
# dof6 outputs against their own vacuum fall to an `impact` end.
lv_add_unit_test(test_iip unit/test_iip.c)
