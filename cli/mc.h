/* mc.h - `lvsim mc` under mpirun (cli/mc_mpi.c, the module lvsim_mpi.so built only when MPI
 * is found, loaded by cmd_mc.c only when mpirun started the process): the same campaign split
 * across ranks; rank 0 owns the database and hands out run indices in chunks as ranks ask for
 * them (dynamic load balancing). */
#ifndef LVSIM_CLI_MC_H
#define LVSIM_CLI_MC_H

#include "lvsim/lv_campaign.h"

/* The MPI world's size when this process was started by mpirun (OpenMPI, or a PMI launcher),
 * else 1; without MPI support always 1. */
int mc_mpi_world_size(void);

/* This process's rank as the launcher tells it before MPI starts (OMPI_COMM_WORLD_RANK,
 * PMI_RANK), else 0: rank 0 alone owns the campaign folder. */
int mc_mpi_env_rank(void);

/* Runs the campaign on every rank (each with o->threads worker threads; rank 0 also stores).
 * Returns the library status on rank 0 (*rank0 = 1), LV_OK elsewhere (*rank0 = 0). Without
 * MPI in the world (world size 1) the threaded campaign; else lv_mc_mpi_run of the module
 * lvsim_mpi.so (<libdir>/lvsim/, beside liblvsim_post), loaded now: LV_ERR_IO naming why
 * when it cannot be. */
lv_status mc_mpi_run(const lv_mission *m, const lv_campaign_options *o, lv_campaign_progress *out,
                     int *rank0, lv_err *err);

/* The module's entry point (mc_mpi.c), as mc_mpi_run under mpirun. */
lv_status lv_mc_mpi_run(const lv_mission *m, const lv_campaign_options *o,
                        lv_campaign_progress *out, int *rank0, lv_err *err);
typedef lv_status (*lv_mc_mpi_run_fn)(const lv_mission *m, const lv_campaign_options *o,
                                      lv_campaign_progress *out, int *rank0, lv_err *err);

#endif
