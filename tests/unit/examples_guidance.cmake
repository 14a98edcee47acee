# The guided-flight examples (issue 12): examples/kourou-leo (ascent to a low Earth orbit) and
# examples/kourou-rtls (the same vehicle, booster return to the launch site) run through the
# public API; the test checks what their READMEs promise (orbit, limits, jettison, landing).
lv_add_unit_test(test_examples_guidance unit/test_examples_guidance.c)
# The winged reusable launcher of issue 14 (examples/rlv-hthl): take-off roll, ascent,
# separation, the upper stage's orbit and the main stage's return over the runway threshold.
lv_add_unit_test(test_example_rlv unit/test_example_rlv.c)
# The 6-DoF example of issue 15 (examples/two-stage-6dof): the first stage under attitude
# control through max-q to staging, the upper stage to orbit.
lv_add_unit_test(test_example_6dof unit/test_example_6dof.c)
