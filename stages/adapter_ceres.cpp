// seamquad: Ceres adapter (C++17). Wraps ceres::Solve behind the C interface
// of sq_ceres_adapter.h: it translates the C problem description into Ceres
// residual blocks and options and copies the summary back. No geometry here.
#include "sq_ceres_adapter.h"

#include <ceres/ceres.h>

#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

namespace {

// Residuals with their derivatives, both from the C callback.
class ResidualCost final : public ceres::CostFunction {
public:
    ResidualCost(const sq_nlls_problem *p, uint32_t r) : p_(p), r_(r)
    {
        set_num_residuals(static_cast<int>(p->res_dim[r]));
        for (uint32_t i = p->res_off[r]; i < p->res_off[r + 1]; i++)
            mutable_parameter_block_sizes()->push_back(static_cast<int>(p->block_size));
    }
    bool Evaluate(double const *const *param, double *residual, double **jac) const override
    {
        return p_->residual(p_->user, r_, param, residual, jac) != 0;
    }

private:
    const sq_nlls_problem *p_;
    uint32_t r_;
};

// Zero residual whose evaluation fails where the C predicate says infeasible.
class FeasibilityCost final : public ceres::CostFunction {
public:
    FeasibilityCost(const sq_nlls_problem *p, uint32_t c) : p_(p), c_(c)
    {
        set_num_residuals(1);
        for (uint32_t i = p->con_off[c]; i < p->con_off[c + 1]; i++)
            mutable_parameter_block_sizes()->push_back(static_cast<int>(p->block_size));
    }
    bool Evaluate(double const *const *param, double *residual, double **jac) const override
    {
        if (!p_->feasible(p_->user, c_, param)) return false;
        residual[0] = 0.0;
        if (jac)
            for (uint32_t i = 0; i < p_->con_off[c_ + 1] - p_->con_off[c_]; i++)
                if (jac[i]) std::memset(jac[i], 0, p_->block_size * sizeof(double));
        return true;
    }

private:
    const sq_nlls_problem *p_;
    uint32_t c_;
};

void copy_str(char *dst, size_t n, const std::string &s)
{
    std::snprintf(dst, n, "%s", s.c_str());
}

}  // namespace

extern "C" void sq_nlls_options_default(sq_nlls_options *o)
{
    o->max_iterations = 50;
    o->function_tolerance = 1e-8;
    o->gradient_tolerance = 1e-10;
    o->parameter_tolerance = 1e-8;
    o->num_threads = 1;
    o->max_linear_iterations = 500;
    o->initial_trust_region_radius = 1e4;
}

extern "C" sq_status sq_nlls_solve(const sq_nlls_problem *p, const sq_nlls_options *o,
                                   sq_nlls_summary *s, sq_error *err)
{
    std::memset(s, 0, sizeof *s);
    if (!p || !o || !p->x || !p->residual || p->block_size == 0 || (p->ncon && !p->feasible))
        return sq_error_set(err, SQ_ERR_ARGUMENT, "least squares: incomplete problem description");
    try {
        ceres::Problem::Options po;  // Problem owns (and deletes) the cost functions
        ceres::Problem problem(po);
        const int bs = static_cast<int>(p->block_size);
        for (uint32_t b = 0; b < p->nblock; b++) problem.AddParameterBlock(p->x + (size_t)b * bs, bs);
        std::vector<double *> blocks;
        for (uint32_t r = 0; r < p->nres; r++) {
            blocks.clear();
            for (uint32_t i = p->res_off[r]; i < p->res_off[r + 1]; i++)
                blocks.push_back(p->x + (size_t)p->res_param[i] * bs);
            problem.AddResidualBlock(new ResidualCost(p, r), nullptr, blocks);
        }
        for (uint32_t c = 0; c < p->ncon; c++) {
            blocks.clear();
            for (uint32_t i = p->con_off[c]; i < p->con_off[c + 1]; i++)
                blocks.push_back(p->x + (size_t)p->con_param[i] * bs);
            problem.AddResidualBlock(new FeasibilityCost(p, c), nullptr, blocks);
        }
        if (p->constant)
            for (uint32_t b = 0; b < p->nblock; b++)
                if (p->constant[b]) problem.SetParameterBlockConstant(p->x + (size_t)b * bs);

        ceres::Solver::Options so;
        so.minimizer_type = ceres::TRUST_REGION;
        so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
        // Conjugate gradients on the normal equations (block Jacobi
        // preconditioner; the caller bounds the iterations per step):
        // sparse products instead of a Cholesky factorization per step
        // (docs/smooth.md, "Cost").
        so.linear_solver_type = ceres::CGNR;
        so.preconditioner_type = ceres::JACOBI;
        if (o->max_linear_iterations > 0) so.max_linear_solver_iterations = o->max_linear_iterations;
        so.max_num_iterations = o->max_iterations;
        if (o->initial_trust_region_radius > 0) {
            so.initial_trust_region_radius = o->initial_trust_region_radius;
            if (so.max_trust_region_radius < so.initial_trust_region_radius)
                so.max_trust_region_radius = so.initial_trust_region_radius;
        }
        so.function_tolerance = o->function_tolerance;
        so.gradient_tolerance = o->gradient_tolerance;
        so.parameter_tolerance = o->parameter_tolerance;
        so.num_threads = o->num_threads > 0 ? o->num_threads : 1;
        so.logging_type = ceres::SILENT;  // the library never prints
        so.minimizer_progress_to_stdout = false;

        std::string why;
        if (!so.IsValid(&why))
            return sq_error_set(err, SQ_ERR_INTERNAL, "least squares: invalid Ceres options: %s", why.c_str());
        ceres::Solver::Summary sum;
        ceres::Solve(so, &problem, &sum);
        s->initial_cost = sum.initial_cost;
        s->final_cost = sum.final_cost;
        s->iterations = static_cast<int>(sum.iterations.size());
        s->successful_steps = sum.num_successful_steps;
        s->unsuccessful_steps = sum.num_unsuccessful_steps;
        s->converged = sum.termination_type == ceres::CONVERGENCE;
        s->seconds = sum.total_time_in_seconds;
        copy_str(s->linear_solver, sizeof s->linear_solver,
                 std::string(ceres::LinearSolverTypeToString(sum.linear_solver_type_used)) + "/" +
                     ceres::PreconditionerTypeToString(so.preconditioner_type));
        copy_str(s->message, sizeof s->message, sum.message);
        if (sum.termination_type == ceres::FAILURE || sum.termination_type == ceres::USER_FAILURE)
            return sq_error_set(err, SQ_ERR_SOLVER, "least squares: Ceres failed: %s", sum.message.c_str());
        return SQ_OK;
    } catch (const std::bad_alloc &) {
        return sq_error_set(err, SQ_ERR_NOMEM, "least squares: out of memory");
    } catch (const std::exception &e) {
        return sq_error_set(err, SQ_ERR_INTERNAL, "least squares: %s", e.what());
    }
}
