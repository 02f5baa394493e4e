// The Newton iteration of a load step (doc/formulation.md, "Stopping
// criteria", "Adaptive stopping"): the loop, the tangent predictor, the
// measure of an iterate, the linear solve of the Newton system
// (NewtonSolver), and the view of the problem it reads. What is done when the
// system is singular is in newton_singular_system.cc, the line search that
// moves the iterate along an update in newton_line_search.cc.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
#include <stabilized_lagrangian/solver/newton_solver.h>
#include <stabilized_lagrangian/solver/iterative_solver.h>
#include <stabilized_lagrangian/solver/linear_solver.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /**
     * The forcing term η_k of an inexact Newton step, Eisenstat–Walker (1996)
     * choice 2: η_k = γ (|F_k| / |F_k−1|)² with γ = 0.9, safeguarded by
     * γ η_k−1² where that is above 0.1; @p maximum at the first iteration or
     * without a positive previous residual @p previous_residual.
     * @p residual is |F_k|, @p previous_forcing η_k−1.
     */
    double
    eisenstat_walker_forcing(const double residual,
                             const double previous_residual,
                             const double previous_forcing,
                             const bool   first_iteration,
                             const double maximum)
    {
      double forcing = maximum;
      if (!first_iteration && std::isfinite(previous_residual) && previous_residual > 0.)
        {
          const double gamma = 0.9;
          forcing            = gamma * std::pow(residual / previous_residual, 2);
          if (gamma * previous_forcing * previous_forcing > 0.1)
            forcing = std::max(forcing, gamma * previous_forcing * previous_forcing);
        }
      return forcing;
    }

    /**
     * Solve the Newton system @p matrix @p update = @p rhs by GMRES to the
     * relative tolerance @p forcing in the norm weighted by @p row_weights,
     * and add the solver's iterations and phase times to @p work. False, with
     * the reason printed, when GMRES does not reach the tolerance: the
     * direct solver then takes the system.
     */
    bool
    solve_by_gmres(LinearSolvers::BlockIterativeSolver  &solver,
                   const TrilinosWrappers::SparseMatrix &matrix,
                   TrilinosWrappers::MPI::Vector        &update,
                   const TrilinosWrappers::MPI::Vector  &rhs,
                   const TrilinosWrappers::MPI::Vector  &row_weights,
                   const double                          forcing,
                   WorkCounters                         &work,
                   const ConditionalOStream             &pcout)
    {
      const bool solved = solver.solve(matrix, update, rhs, row_weights, forcing);
      work.krylov_iterations += solver.last_iterations();
      work.amg_setup_seconds += solver.last_times().amg_setup;
      work.schur_seconds += solver.last_times().schur;
      work.krylov_seconds += solver.last_times().krylov;
      work.schur_solve_seconds += solver.last_times().schur_solves;
      if (!solved)
        {
          pcout << "  Newton: " << solver.last_error()
                << "; this system is solved by the direct solver\n";
          ++work.iterative_fallbacks;
        }
      return solved;
    }
  } // namespace

  template <int dim>
  NewtonSolver<dim>::NewtonSolver(const View &problem)
      : problem(problem)
  {
  }

  template <int dim>
  bool
  NewtonSolver<dim>::solve(StepStatistics    &stats,
                           const unsigned int k,
                           const unsigned int j,
                           const unsigned int i)
  {
    // the open/stick/slip statuses of the iterates, when Newton decides them
    Progress progress(problem.loops.linearised(Loop::status));
    // No Newton loop of this attempt has converged yet (a loop that fails
    // fails the attempt): this is the step's first Newton solve.
    if (stats.inner_loops.empty() && problem.dirichlet_increment_nonzero)
      {
        if (!predictor_step(stats, progress))
          return false;
      }
    else
      // The first assembly (with the Jacobian) is at the iterate the outer
      // loops hand over; afterwards the residual at each new iterate comes
      // from the line search, and the Jacobian is assembled only when another
      // solve follows.
      problem.assemble(true);
    for (;;)
      {
        Measure measured;
        if (!measure_iterate(progress, measured))
          return false;
        const bool converged = measured.measure <= measured.tolerance;
        if (converged || adaptive_stop(progress, measured.scaled))
          {
            stats.adaptive_stops += !converged;
            stats.inner_loops.push_back(InnerLoopRecord{
                k, j, i, progress.iteration, measured.residual, measured.scaled, 0});
            stats.newton_iterations += progress.iteration;
            stats.final_residual = measured.residual;
            stats.final_scaled   = measured.scaled;
            return true;
          }
        TrilinosWrappers::MPI::Vector update;
        if (!newton_direction(stats, progress, measured, update))
          return false;
        advance(progress, update, measured.residual, problem.parameters.line_search_steps);
      }
  }

  template <int dim>
  bool
  NewtonSolver<dim>::predictor_step(StepStatistics &stats, Progress &progress)
  {
    // K Δū is added to the residual of this assembly alone
    problem.dirichlet_predictor = true;
    problem.assemble(true);
    problem.dirichlet_predictor = false;
    Measure                       measured;
    TrilinosWrappers::MPI::Vector update;
    if (!measure_iterate(progress, measured) ||
        !newton_direction(stats, progress, measured, update))
      return false;
    // the Dirichlet increment (zero in the update's constrained rows)
    TrilinosWrappers::MPI::Vector increment(problem.locally_owned, problem.communicator);
    increment = problem.dirichlet_increment;
    update += increment;
    // the predictor step is taken whole: it carries the boundary data
    advance(progress, update, measured.residual, 0);
    return true;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::measure_iterate(Progress &progress, Measure &measured) const
  {
    if (!problem.inadmissible_state.empty())
      {
        problem.pcout << "  Newton: " << problem.inadmissible_state << "\n";
        return false;
      }
    measured.residual = problem.residual_norm();
    if (!std::isfinite(measured.residual))
      {
        problem.pcout << "  Newton: the residual is not finite\n";
        return false;
      }
    measured.scaled  = problem.scaled_residual().largest();
    measured.measure = problem.parameters.newton_criterion == Parameters::ResidualCriterion::scaled
                           ? measured.scaled
                           : measured.residual;
    if (progress.iteration == 0)
      progress.first_measure = measured.measure;
    if (problem.log_newton)
      log_iterate(progress.iteration);
    measured.tolerance =
        problem.parameters.newton_tolerance *
        (problem.parameters.newton_criterion == Parameters::ResidualCriterion::relative
             ? progress.first_measure
             : 1.);
    return true;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::newton_direction(const StepStatistics          &stats,
                                      Progress                      &progress,
                                      const Measure                 &measured,
                                      TrilinosWrappers::MPI::Vector &update)
  {
    if (measured.measure > 0.)
      progress.needed_reduction = measured.tolerance / measured.measure;
    return may_iterate(stats, progress, measured) && solve_for_update(progress, update);
  }

  template <int dim>
  bool
  NewtonSolver<dim>::may_iterate(const StepStatistics &stats,
                                 const Progress       &progress,
                                 const Measure        &measured)
  {
    const unsigned int iteration = progress.iteration;
    if (iteration == problem.parameters.newton_max_iterations)
      {
        problem.pcout << "  Newton: residual " << measured.residual << ' ' << problem.force_unit
                      << " (" << measured.measure << " against the criterion's tolerance "
                      << measured.tolerance << ") after " << iteration
                      << " iterations (Nonlinear solver/Newton/Maximum iterations)\n";
        return false;
      }
    if (stats.newton_iterations + iteration >= problem.parameters.max_newton_per_step)
      {
        problem.pcout
            << "  Newton: " << stats.newton_iterations + iteration
            << " iterations in this load step (Nonlinear solver/Maximum Newton iterations "
               "per load step)\n";
        return false;
      }
    // nothing in contact and a rigid motion free: the system is singular,
    // and no smaller load step makes it less so
    if (!problem.free_rigid_motions.empty() && problem.points_in_contact() == 0)
      {
        problem.unrecoverable_failure =
            "the body is not supported: no contact point is in contact (the loads pull it off "
            "the obstacle) and the Dirichlet conditions leave " +
            problem.free_rigid_motions +
            " free. Hold it by a prescribed displacement, or load it towards the obstacle";
        problem.pcout << "  Newton: " << problem.unrecoverable_failure << ".\n";
        return false;
      }
    return true;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::solve_for_update(Progress &progress, TrilinosWrappers::MPI::Vector &update)
  {
    if (progress.newton_decides_statuses)
      progress.watch.seen.push_back(problem.contact.conditions().statuses());
    if (!progress.jacobian_current)
      problem.assemble(true);
    update.reinit(problem.locally_owned, problem.communicator);
    problem.system_rhs *= -1.;
    bool solved = false;
    {
      TimerOutput::Scope scope(problem.timer, "linear solve");
      if (problem.iterative_solver)
        {
          // a tenth of the reduction that meets the Newton tolerance now, or
          // Eisenstat–Walker's forcing term
          const double maximum = problem.linear_solver_parameters.maximum_forcing_term;
          double       forcing = 0.1 * progress.needed_reduction;
          if (problem.linear_solver_parameters.eisenstat_walker)
            forcing = eisenstat_walker_forcing(problem.residual_norm(),
                                               progress.previous_residual,
                                               progress.forcing_term,
                                               progress.iteration == 0,
                                               maximum);
          forcing               = std::clamp(forcing, 1e-10, maximum);
          progress.forcing_term = forcing;
          solved                = solve_by_gmres(*problem.iterative_solver,
                                  problem.system_matrix,
                                  update,
                                  problem.system_rhs,
                                  problem.residual_scaling,
                                  forcing,
                                  problem.work,
                                  problem.pcout);
        }
      if (!solved)
        solved = problem.direct_solver->solve(problem.system_matrix, update, problem.system_rhs);
    }
    ++problem.work.newton_iterations;
    if (!problem.direct_solver->last_retry().empty())
      problem.pcout << "  Newton: " << problem.direct_solver->last_retry() << "\n";
    if (!solved)
      {
        const std::string &error = problem.direct_solver->last_error();
        problem.pcout << "  Newton: the linear solver failed: " << error << ".\n";
        // a smaller load step has the same matrix size and structure
        if (error.find("memory") != std::string::npos ||
            error.find("work space") != std::string::npos)
          problem.unrecoverable_failure = "the linear solver failed: " + error;
        if (error.find("singular") == std::string::npos)
          return false;
      }
    std::string singular = "the linear solver found the matrix singular";
    if (solved)
      {
        problem.newton_constraints.distribute(update);
        singular = problem.bounds.implausible(
            update, problem.locally_owned_u, "the Newton update", problem.communicator);
      }
    if (!singular.empty())
      {
        if (start_holding_contact())
          {
            problem.assemble(true);
            const bool repeated                        = solve_for_update(progress, update);
            problem.contact_start.provisional_pressure = 0.;
            problem.contact_start.approach_gap         = 0.;
            return repeated;
          }
        if (!fold_friction_for_slipping_contact())
          report_near_singular(singular);
        return false;
      }
    // the body has been lowered by this solve: the gaps are its own now
    problem.contact_start.approach_gap = 0.;
    if (problem.parameters.adaptive_stopping)
      progress.update_energy = displacement_energy(update);
    return true;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::plausible_converged_state() const
  {
    const std::string implausible = problem.bounds.implausible(
        problem.solution, problem.locally_owned_u, "the converged state", problem.communicator);
    if (!implausible.empty())
      problem.pcout << "  " << implausible
                    << ": the loops converged to a state no quasi-static load "
                    << "step reaches, which is not accepted\n";
    return implausible.empty();
  }

  template <int dim>
  double
  NewtonSolver<dim>::displacement_energy(const TrilinosWrappers::MPI::Vector &update) const
  {
    // (δuᵀ K δu)^½ with the multiplier rows of δ left out: the tangent's
    // energy of the displacement part (the matrix of the last solve)
    TrilinosWrappers::MPI::Vector displacement(problem.locally_owned, problem.communicator);
    TrilinosWrappers::MPI::Vector product(problem.locally_owned, problem.communicator);
    for (const auto index : problem.locally_owned_u)
      displacement(index) = update(index);
    displacement.compress(VectorOperation::insert);
    problem.system_matrix.vmult(product, displacement);
    return std::sqrt(std::abs(displacement * product));
  }

  template <int dim>
  bool
  NewtonSolver<dim>::adaptive_stop(Progress &progress, const double scaled_residual)
  {
    // Adaptive stopping (doc/formulation.md, "Adaptive stopping"; Ern and
    // Vohralik, SISC 35, 2013): the last update bounds the linearisation
    // error of the iterate it led to (by far, once Newton converges
    // quadratically); once it is below a fraction of the discretisation
    // error estimated at that iterate, further iterations cannot change the
    // answer beyond what the mesh resolves. The update's energy leaves out
    // the multipliers: the scaled residual, whose blocks include the gap and
    // the slip, stands for them.
    // An earlier estimate only spares a check, never stops a loop: with one
    // made per Newton loop and reused to stop, the J2 patin's outer loops
    // cycled (1445 Newton iterations against 124; doc/formulation.md,
    // "Adaptive stopping").
    if (!problem.parameters.adaptive_stopping || progress.iteration == 0 ||
        !std::isfinite(progress.update_energy) ||
        !below_discretisation_error(progress.update_energy, scaled_residual))
      return false;
    if (problem.log_newton)
      problem.pcout << "    Newton stops adaptively: last update " << progress.update_energy
                    << " sqrt(N mm), scaled residual " << scaled_residual
                    << ", estimated discretisation error " << estimate.error
                    << " sqrt(N mm), relative " << estimate.relative() << "\n";
    return true;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::below_discretisation_error(const double change_energy,
                                                const double relative_change)
  {
    // No estimate is made while the change is above twice what the last
    // estimate (of any loop, on this mesh or an earlier one) allows: the
    // estimate moves far less than the changes. Where it grew since, a check
    // that might have stopped is skipped: fewer early stops, never a wrong one.
    const double fraction = problem.parameters.adaptive_fraction;
    if (estimate.error > 0. && (change_energy > 2. * fraction * estimate.error ||
                                relative_change > 2. * fraction * estimate.relative()))
      return false;
    estimate = problem.estimated_energy_error();
    return change_energy <= fraction * estimate.error &&
           relative_change <= fraction * estimate.relative();
  }

  template <int dim>
  void
  NewtonSolver<dim>::log_iterate(const unsigned int iteration) const
  {
    const ScaledResidual scaled = problem.scaled_residual();
    std::ostringstream   line;
    line << std::setprecision(6) << "    Newton " << iteration << ": residual "
         << problem.residual_norm() << ' ' << problem.force_unit << "; scaled: force ";
    // a body at rest has no force to measure the residual against yet: the
    // criterion counts it as not converged (ScaledResidual), the log says why
    if (std::isfinite(scaled.force))
      line << scaled.force;
    else
      line << "(no scale: the body carries no force yet)";
    line << ", gap " << scaled.gap << ", slip " << scaled.slip << "\n";
    problem.pcout << line.str();
  }

  template <int dim>
  typename NewtonSolver<dim>::View
  ContactProblem<dim>::newton_view()
  {
    return typename NewtonSolver<dim>::View{
        solver_parameters,
        linear_solver_parameters,
        output_parameters.log_newton,
        mpi_communicator,
        pcout,
        timer,
        force_unit(dim, axisymmetric, false),
        locally_owned,
        locally_owned_u,
        newton_constraints,
        system_matrix,
        residual_scaling,
        external_force,
        dirichlet_increment,
        dirichlet_increment_nonzero,
        inadmissible_state,
        direct_solver,
        iterative_solver,
        bounds,
        free_rigid_motions,
        negligible_pressure,
        loops,
        contact,
        law,
        solution,
        system_rhs,
        dirichlet_predictor,
        contact_start,
        unrecoverable_failure,
        work,
        [this](const bool with_matrix) { assemble_newton_system(with_matrix); },
        [this]() { return SystemAssembler<dim>(assembly_view()).residual_norm(); },
        [this]() { return SystemAssembler<dim>(assembly_view()).scaled_residual(); },
        [this]() { update_ghosts(); },
        [this]() { return estimated_energy_error(); },
        [this]() { return contact.points_in_contact(); },
        [this]() { close_nearest_points(); },
        [this]() { return contact_zones.any_friction(); },
        [this]() { return contact_zones.any_pressure_dependent_threshold(); },
        [this](const typename NewtonSolver<dim>::PointVisitor &f) { contact.for_each_point(f); },
        [this](const std::vector<std::vector<unsigned char>> &seen,
               const std::vector<unsigned char>              &statuses,
               const unsigned int                             end) {
          return first_equal(seen, statuses, end, mpi_communicator);
        }};
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)                                                                       \
  template NewtonSolver<dim>::NewtonSolver(const View &);                                         \
  template bool NewtonSolver<dim>::solve(                                                         \
      StepStatistics &, unsigned int, unsigned int, unsigned int);                                \
  template bool   NewtonSolver<dim>::predictor_step(StepStatistics &, Progress &);                \
  template bool   NewtonSolver<dim>::measure_iterate(Progress &, Measure &) const;                \
  template bool   NewtonSolver<dim>::adaptive_stop(Progress &, double);                           \
  template bool   NewtonSolver<dim>::below_discretisation_error(double, double);                  \
  template double NewtonSolver<dim>::displacement_energy(const TrilinosWrappers::MPI::Vector &)   \
      const;                                                                                      \
  template bool NewtonSolver<dim>::newton_direction(                                              \
      const StepStatistics &, Progress &, const Measure &, TrilinosWrappers::MPI::Vector &);      \
  template bool NewtonSolver<dim>::may_iterate(                                                   \
      const StepStatistics &, const Progress &, const Measure &);                                 \
  template bool NewtonSolver<dim>::solve_for_update(Progress &, TrilinosWrappers::MPI::Vector &); \
  template bool NewtonSolver<dim>::plausible_converged_state() const;                             \
  template void NewtonSolver<dim>::log_iterate(unsigned int) const;                               \
  template typename NewtonSolver<dim>::View ContactProblem<dim>::newton_view();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
