/* seamquad: Ceres adapter, a generic sparse nonlinear least-squares solver
 * behind a C interface (the only C++ in stages/, see docs/smooth.md).
 *
 * The split: C code decides what is optimized (parameter blocks, which
 * residuals exist, what they compute, which states are feasible); the
 * adapter only hands that description to Ceres and returns the result.
 *
 *   minimize  1/2 sum_r |f_r(x_{r,0}, ..., x_{r,k-1})|^2
 *
 * over nblock parameter blocks of block_size doubles each. Residual block r
 * depends on the parameter blocks res_param[res_off[r] .. res_off[r+1]-1]
 * (distinct) and has res_dim[r] components, computed with their
 * derivatives by the C callback `residual`.
 *
 * Feasibility: constraint block c over the parameter blocks
 * con_param[con_off[c] .. con_off[c+1]-1] is a predicate `feasible`. A trial
 * step on which some predicate is false is rejected (Ceres treats it as a
 * step of infinite cost and shrinks the trust region), so every accepted
 * iterate is feasible when the start is. The start must be feasible. */
#ifndef SQ_CERES_ADAPTER_H
#define SQ_CERES_ADAPTER_H

#include <stdint.h>

#include "sq_error.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Residuals of block `r` at the given parameter blocks (param[i] points to
 * block_size doubles) and, when jac is not NULL, their derivatives: jac[i]
 * (when not NULL) gets the res_dim[r] x block_size matrix, row-major, of
 * the residuals' derivatives by the i-th parameter block of r. Returns 1 on
 * success, 0 when undefined there. */
typedef int (*sq_nlls_residual_fn)(void *user, uint32_t r, const double *const *param, double *residual,
                                   double **jac);

/* 1 when the parameter blocks of constraint block `c` are feasible. */
typedef int (*sq_nlls_feasible_fn)(void *user, uint32_t c, const double *const *param);

typedef struct sq_nlls_problem {
    uint32_t nblock, block_size;
    double *x;                  /* nblock*block_size: start in, result out */
    uint32_t nres;
    const uint32_t *res_off;    /* nres+1                                  */
    const uint32_t *res_param;  /* res_off[nres] block indices             */
    const uint32_t *res_dim;    /* nres                                    */
    sq_nlls_residual_fn residual;
    uint32_t ncon;              /* may be 0                                */
    const uint32_t *con_off;    /* ncon+1                                  */
    const uint32_t *con_param;  /* con_off[ncon]                           */
    sq_nlls_feasible_fn feasible;
    void *user;
    const unsigned char *constant; /* nblock, or NULL: 1 = block held fixed     */
} sq_nlls_problem;

typedef struct sq_nlls_options {
    int max_iterations;         /* Levenberg-Marquardt iterations          */
    double function_tolerance;  /* relative cost decrease to stop          */
    double gradient_tolerance;  /* max-norm of the projected gradient      */
    double parameter_tolerance; /* relative step size                      */
    int num_threads;            /* >= 1; callbacks must be thread-safe if > 1 */
    int max_linear_iterations;  /* conjugate-gradient iterations per step  */
                                /* (500: Ceres' default)                   */
    double initial_trust_region_radius; /* LM's first trust region (1e4, as  */
                                /* Ceres'; 1 / the first damping weight)   */
} sq_nlls_options;

typedef struct sq_nlls_summary {
    double initial_cost, final_cost;
    int iterations, successful_steps, unsuccessful_steps;
    int converged;              /* a tolerance was met                     */
    double seconds;
    char linear_solver[48];     /* what Ceres used                         */
    char message[256];          /* Ceres' termination message              */
} sq_nlls_summary;

/* Defaults: 50 iterations, tolerances 1e-8, 1e-10, 1e-8, 1 thread,
 * 500 linear iterations, trust region 1e4. */
void sq_nlls_options_default(sq_nlls_options *o);

/* Solves with Levenberg-Marquardt, each step's normal equations by
 * conjugate gradients with a block Jacobi preconditioner (Ceres' CGNR).
 * SQ_ERR_SOLVER when Ceres fails (e.g. infeasible or undefined start). */
sq_status sq_nlls_solve(const sq_nlls_problem *p, const sq_nlls_options *o, sq_nlls_summary *s,
                        sq_error *err);

#ifdef __cplusplus
}
#endif
#endif
