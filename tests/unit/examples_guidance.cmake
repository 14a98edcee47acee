# The guided-flight examples (issue 12): examples/kourou-leo (ascent to a low Earth orbit) and
# examples/kourou-rtls (the same vehicle, booster return to the launch site) run through the
# public API; the test checks what their READMEs promise (orbit, limits, jettison, landing).
lv_add_unit_test(test_examples_guidance unit/test_examples_guidance.c)
