/* py_layout.c - the layout of every public structure the Python package mirrors with ctypes
 * (python/lvsim/_lib.py), as the C compiler sees the headers: one line per structure
 * "STRUCT size N" and per field "STRUCT.FIELD offset N". test_python.py compares them with
 * ctypes' view, so a header change not made in _lib.py too fails the suite. */
#include <stddef.h>
#include <stdio.h>

#include "lvsim/lvsim.h"
#include "lvsim/lv_campaign.h"
#include "lvsim/lv_dispersion.h"
#include "lvsim/lv_ocp.h"
#include "lvsim/lv_target.h"

#define S(T) printf(#T " size %zu\n", sizeof(T))
#define F(T, f) printf(#T "." #f " offset %zu\n", offsetof(T, f))

int main(void)
{
    S(lv_law_key); F(lv_law_key, name); F(lv_law_key, type); F(lv_law_key, unit);
    F(lv_law_key, lo); F(lv_law_key, hi); F(lv_law_key, lo_open); F(lv_law_key, hi_open);
    F(lv_law_key, dflt); F(lv_law_key, flags); F(lv_law_key, frames);
    F(lv_law_key, instead_of); F(lv_law_key, needs); F(lv_law_key, choices);
    F(lv_law_key, offset); F(lv_law_key, description);
    S(lv_law_info); F(lv_law_info, name); F(lv_law_info, description); F(lv_law_info, kind);
    F(lv_law_info, form); F(lv_law_info, needs_aero); F(lv_law_info, n_keys);
    F(lv_law_info, keys);
    S(lv_err); F(lv_err, code); F(lv_err, msg);
    S(lv_var); F(lv_var, name); F(lv_var, unit); F(lv_var, description); F(lv_var, start);
    F(lv_var, nominal);
    S(lv_event_def); F(lv_event_def, name); F(lv_event_def, description);
    F(lv_event_def, direction); F(lv_event_def, ends_run);
    /* lv_model_def: the leading fields only (the package reads names and counts) */
    F(lv_model_def, name); F(lv_model_def, description); F(lv_model_def, n_states);
    F(lv_model_def, n_params); F(lv_model_def, n_outputs); F(lv_model_def, n_events);
    F(lv_model_def, states); F(lv_model_def, params); F(lv_model_def, outputs);
    F(lv_model_def, events); F(lv_model_def, inst_size);
    S(lv_mission_info); F(lv_mission_info, name); F(lv_mission_info, description);
    F(lv_mission_info, path); F(lv_mission_info, epoch); F(lv_mission_info, flat_world);
    F(lv_mission_info, planet); F(lv_mission_info, site_lat); F(lv_mission_info, site_lon);
    F(lv_mission_info, n_phases); F(lv_mission_info, n_stages); F(lv_mission_info, n_params);
    S(lv_phase_info); F(lv_phase_info, name); F(lv_phase_info, model); F(lv_phase_info, parent);
    F(lv_phase_info, n_stages); F(lv_phase_info, stages); F(lv_phase_info, method);
    F(lv_phase_info, file_index);
    F(lv_phase_info, handoff_rule);
    S(lv_param_info); F(lv_param_info, name); F(lv_param_info, unit); F(lv_param_info, value);
    F(lv_param_info, line); F(lv_param_info, rule);
    S(lv_sim_stats); F(lv_sim_stats, steps); F(lv_sim_stats, rhs_evals);
    F(lv_sim_stats, jac_evals); F(lv_sim_stats, err_test_fails); F(lv_sim_stats, nonlin_fails);
    F(lv_sim_stats, g_evals); F(lv_sim_stats, state_events); F(lv_sim_stats, time_events);
    F(lv_sim_stats, restarts); F(lv_sim_stats, output_rows); F(lv_sim_stats, cpu_time);
    F(lv_sim_stats, rhs_evals_steps); F(lv_sim_stats, rhs_evals_output);
    F(lv_sim_stats, row_evals);
    S(lv_event_record); F(lv_event_record, t); F(lv_event_record, is_state);
    F(lv_event_record, index); F(lv_event_record, direction); F(lv_event_record, name);
    S(lv_sim_report); F(lv_sim_report, stats); F(lv_sim_report, reason);
    F(lv_sim_report, end_time); F(lv_sim_report, stop_event); F(lv_sim_report, stop_name);
    F(lv_sim_report, method_used); F(lv_sim_report, method_why);
    F(lv_sim_report, n_states); F(lv_sim_report, n_event_log); F(lv_sim_report, event_log);
    S(lv_ref_drift); F(lv_ref_drift, n_rows); F(lv_ref_drift, over_tau);
    F(lv_ref_drift, start_from_reference); F(lv_ref_drift, t_first); F(lv_ref_drift, t_final);
    F(lv_ref_drift, pos_max); F(lv_ref_drift, pos_max_t); F(lv_ref_drift, pos_final);
    F(lv_ref_drift, vel_max); F(lv_ref_drift, vel_max_t); F(lv_ref_drift, vel_final);
    F(lv_ref_drift, mass_max); F(lv_ref_drift, mass_max_t); F(lv_ref_drift, mass_final);
    F(lv_ref_drift, ref_end); F(lv_ref_drift, phase_end);
    S(lv_phase_result); F(lv_phase_result, name); F(lv_phase_result, state);
    F(lv_phase_result, error); F(lv_phase_result, t_start); F(lv_phase_result, t_end);
    F(lv_phase_result, t_stop); F(lv_phase_result, method); F(lv_phase_result, tolerance);
    F(lv_phase_result, report); F(lv_phase_result, end_index); F(lv_phase_result, end_value);
    F(lv_phase_result, n_final); F(lv_phase_result, final_names);
    F(lv_phase_result, final_values); F(lv_phase_result, result_stem);
    F(lv_phase_result, n_event_names); F(lv_phase_result, event_names);
    F(lv_phase_result, n_copied); F(lv_phase_result, mass_from_stages);
    F(lv_phase_result, mass_start); F(lv_phase_result, n_set); F(lv_phase_result, set_names);
    F(lv_phase_result, set_values); F(lv_phase_result, propellant_start);
    F(lv_phase_result, propellant_end); F(lv_phase_result, dry_mass);
    F(lv_phase_result, payload); F(lv_phase_result, result_formats);
    F(lv_phase_result, n_absorbed); F(lv_phase_result, absorbed_names);
    F(lv_phase_result, absorbed_units); F(lv_phase_result, absorbed_values);
    F(lv_phase_result, end_label); F(lv_phase_result, event_labels);
    S(lv_run_options); F(lv_run_options, outdir); F(lv_run_options, threads);
    F(lv_run_options, on_phase); F(lv_run_options, user); F(lv_run_options, output_interval);
    F(lv_run_options, method); F(lv_run_options, tolerance); F(lv_run_options, progress);
    F(lv_run_options, no_rows); F(lv_run_options, result_formats); F(lv_run_options, want);
    F(lv_run_options, stop); F(lv_run_options, max_rows);
    S(lv_body_traj); F(lv_body_traj, stage); F(lv_body_traj, n_rows); F(lv_body_traj, n_cols);
    F(lv_body_traj, names); F(lv_body_traj, units); F(lv_body_traj, values);
    F(lv_body_traj, phase);
    S(lv_sink); F(lv_sink, vt); F(lv_sink, self);
    S(lv_sim_stop); F(lv_sim_stop, name); F(lv_sim_stop, variable); F(lv_sim_stop, value);
    F(lv_sim_stop, direction);
    S(lv_sim_settings); F(lv_sim_settings, start_time); F(lv_sim_settings, stop_time);
    F(lv_sim_settings, number_of_intervals); F(lv_sim_settings, output_interval);
    F(lv_sim_settings, method); F(lv_sim_settings, tolerance); F(lv_sim_settings, fixed_step);
    F(lv_sim_settings, result_file); F(lv_sim_settings, result_formats);
    F(lv_sim_settings, n_initial); F(lv_sim_settings, initial_names);
    F(lv_sim_settings, initial_values); F(lv_sim_settings, n_final);
    F(lv_sim_settings, final_names); F(lv_sim_settings, max_steps);
    F(lv_sim_settings, max_step_size); F(lv_sim_settings, n_sinks); F(lv_sim_settings, sinks);
    F(lv_sim_settings, progress); F(lv_sim_settings, progress_user);
    F(lv_sim_settings, n_stops); F(lv_sim_settings, stops);
    F(lv_sim_settings, stop); F(lv_sim_settings, max_rows);
    S(lv_target_var_info); F(lv_target_var_info, name); F(lv_target_var_info, unit);
    F(lv_target_var_info, param); F(lv_target_var_info, deg); F(lv_target_var_info, lo);
    F(lv_target_var_info, hi); F(lv_target_var_info, start); F(lv_target_var_info, scale);
    F(lv_target_var_info, step);
    S(lv_target_con_info); F(lv_target_con_info, name); F(lv_target_con_info, unit);
    F(lv_target_con_info, phase); F(lv_target_con_info, kind); F(lv_target_con_info, value);
    F(lv_target_con_info, tol);
    S(lv_target_cost_info); F(lv_target_cost_info, present); F(lv_target_cost_info, name);
    F(lv_target_cost_info, unit); F(lv_target_cost_info, phase);
    F(lv_target_cost_info, maximize); F(lv_target_cost_info, scale);
    S(lv_target_iter); F(lv_target_iter, iteration); F(lv_target_iter, solver);
    F(lv_target_iter, event); F(lv_target_iter, note); F(lv_target_iter, x);
    F(lv_target_iter, finals); F(lv_target_iter, residual); F(lv_target_iter, cost);
    F(lv_target_iter, worst); F(lv_target_iter, damping); F(lv_target_iter, step);
    F(lv_target_iter, runs); F(lv_target_iter, phases); F(lv_target_iter, runs_total);
    F(lv_target_iter, phases_total); F(lv_target_iter, wall);
    S(lv_target_eval); F(lv_target_eval, iteration); F(lv_target_eval, purpose);
    F(lv_target_eval, var); F(lv_target_eval, runs_total); F(lv_target_eval, phases_total);
    F(lv_target_eval, wall);
    S(lv_target_settings); F(lv_target_settings, method); F(lv_target_settings, differences);
    F(lv_target_settings, max_iterations); F(lv_target_settings, xtol);
    F(lv_target_settings, ftol); F(lv_target_settings, restarts);
    F(lv_target_settings, threads); F(lv_target_settings, on_iteration);
    F(lv_target_settings, on_evaluation); F(lv_target_settings, user);
    F(lv_target_settings, stop); F(lv_target_settings, max_rows);
    S(lv_target_end_mismatch); F(lv_target_end_mismatch, phase);
    F(lv_target_end_mismatch, phase_name); F(lv_target_end_mismatch, expected);
    F(lv_target_end_mismatch, actual); F(lv_target_end_mismatch, t_end);
    S(lv_ocp_iteration); F(lv_ocp_iteration, iteration); F(lv_ocp_iteration, cost);
    F(lv_ocp_iteration, inf_pr); F(lv_ocp_iteration, inf_du); F(lv_ocp_iteration, mu);
    F(lv_ocp_iteration, step); F(lv_ocp_iteration, wall); F(lv_ocp_iteration, segments);
    F(lv_ocp_iteration, restoration);
    S(lv_ocp_settings); F(lv_ocp_settings, threads); F(lv_ocp_settings, max_iterations);
    F(lv_ocp_settings, print_level); F(lv_ocp_settings, on_iteration);
    F(lv_ocp_settings, user); F(lv_ocp_settings, stop);
    S(lv_ocp_result); F(lv_ocp_result, outcome); F(lv_ocp_result, ipopt_status);
    F(lv_ocp_result, ipopt_text); F(lv_ocp_result, iterations); F(lv_ocp_result, cost);
    F(lv_ocp_result, cost_start); F(lv_ocp_result, max_violation);
    F(lv_ocp_result, n_violated); F(lv_ocp_result, n_vars); F(lv_ocp_result, n_cons);
    F(lv_ocp_result, nnz_jac); F(lv_ocp_result, n_groups); F(lv_ocp_result, segments);
    F(lv_ocp_result, evaluations); F(lv_ocp_result, wall); F(lv_ocp_result, cpu);
    F(lv_ocp_result, wall_jac); F(lv_ocp_result, wall_eval); F(lv_ocp_result, last_failure);
    S(lv_target_result); F(lv_target_result, converged); F(lv_target_result, cancelled);
    F(lv_target_result, reason); F(lv_target_result, method); F(lv_target_result, n_vars);
    F(lv_target_result, n_cons); F(lv_target_result, x); F(lv_target_result, finals);
    F(lv_target_result, residual); F(lv_target_result, met); F(lv_target_result, cost);
    F(lv_target_result, worst); F(lv_target_result, iterations); F(lv_target_result, runs);
    F(lv_target_result, phases); F(lv_target_result, wall);
    F(lv_target_result, n_end_mismatch); F(lv_target_result, end_mismatch);
    S(lv_disp_info); F(lv_disp_info, name); F(lv_disp_info, unit); F(lv_disp_info, dist);
    F(lv_disp_info, kind); F(lv_disp_info, relative); F(lv_disp_info, nominal);
    F(lv_disp_info, mean); F(lv_disp_info, sigma); F(lv_disp_info, min); F(lv_disp_info, max);
    F(lv_disp_info, param); F(lv_disp_info, group); F(lv_disp_info, stream);
    F(lv_disp_info, line); F(lv_disp_info, column);
    S(lv_campaign_progress); F(lv_campaign_progress, total); F(lv_campaign_progress, done);
    F(lv_campaign_progress, this_session); F(lv_campaign_progress, failed);
    F(lv_campaign_progress, elapsed); F(lv_campaign_progress, rate);
    F(lv_campaign_progress, eta); F(lv_campaign_progress, impacts);
    F(lv_campaign_progress, crashed);
    S(lv_campaign_options); F(lv_campaign_options, n_runs); F(lv_campaign_options, seed);
    F(lv_campaign_options, threads); F(lv_campaign_options, db_path);
    F(lv_campaign_options, resume); F(lv_campaign_options, overwrite);
    F(lv_campaign_options, keep_runs); F(lv_campaign_options, keep_dir);
    F(lv_campaign_options, method); F(lv_campaign_options, tolerance);
    F(lv_campaign_options, output_interval); F(lv_campaign_options, progress);
    F(lv_campaign_options, user); F(lv_campaign_options, stop);
    F(lv_campaign_options, max_rows);
    S(lv_output_estimate); F(lv_output_estimate, duration); F(lv_output_estimate, rows);
    F(lv_output_estimate, n_signals); F(lv_output_estimate, bytes_mat);
    F(lv_output_estimate, bytes_csv); F(lv_output_estimate, bounded);
    S(lv_outdir_record); F(lv_outdir_record, command); F(lv_outdir_record, status);
    F(lv_outdir_record, mission_name); F(lv_outdir_record, n_notes); F(lv_outdir_record, notes);
    return 0;
}
