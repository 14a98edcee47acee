# Missions: the YAML parser, the phase-model types and their registry, the loaded mission
# (immutable), runs of it, sequential versus end-to-end; the `targeting:` section.
list(APPEND LV_SOURCES
  src/mission/yaml_tree.c
  src/mission/parse.c
  src/mission/parse_env.c
  src/mission/parse_kit.c
  src/mission/parse_params.c
  src/mission/parse_phase.c
  src/mission/parse_tree.c
  src/mission/parse_vehicle.c
  src/mission/engine_run.c
  src/mission/env.c
  src/mission/aero_def.c
  src/mission/guidance_def.c
  src/mission/targeting_def.c
  src/mission/ocp_def.c
  src/mission/dispersion_def.c
  src/mission/dispersion.c
  src/mission/phase_types.c
  src/mission/phase_kit.c
  src/mission/reference.c
  src/mission/phase_flat6.c
  src/mission/phase_dof3.c
  src/mission/phase_runway.c
  src/mission/phase_dof6.c
  src/mission/mission.c
  src/mission/run.c
  src/mission/compare.c
  src/mission/run_estimate.c
  src/mission/output_check.c
  src/mission/phase_types_api.c)
