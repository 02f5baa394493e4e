// The Newton iteration of a load step (doc/formulation.md, "Stopping
// criteria", "Adaptive stopping"): the loop, the tangent predictor, the
// measure of an iterate, the linear solve of the Newton system and what is
// done when it is singular. The line search that moves the iterate along an
// update is in newton_line_search.cc.

#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>

#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/solver/contact_problem.h>
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
  std::vector<unsigned char>
  ContactProblem<dim>::point_statuses()
  {
    return conditions->statuses();
  }

  template <int dim>
  bool
  ContactProblem<dim>::newton_loop(StepStatistics    &stats,
                                   const unsigned int k,
                                   const unsigned int j,
                                   const unsigned int i)
  {
    // the open/stick/slip statuses of the iterates, when Newton decides them
    NewtonProgress progress(loops.linearised(Loop::status));
    // No Newton loop of this attempt has converged yet (a loop that fails
    // fails the attempt): this is the step's first Newton solve.
    if (stats.inner_loops.empty() && dirichlet_increment_nonzero)
      {
        if (!predictor_step(stats, progress))
          return false;
      }
    else
      // The first assembly (with the Jacobian) is at the iterate the outer
      // loops hand over; afterwards the residual at each new iterate comes
      // from the line search, and the Jacobian is assembled only when another
      // solve follows.
      assemble_newton_system(true);
    for (;;)
      {
        NewtonMeasure measured;
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
        advance(progress, update, measured.residual, solver_parameters.line_search_steps);
      }
  }

  template <int dim>
  bool
  ContactProblem<dim>::predictor_step(StepStatistics &stats, NewtonProgress &progress)
  {
    // K Δū is added to the residual of this assembly alone
    dirichlet_predictor = true;
    assemble_newton_system(true);
    dirichlet_predictor = false;
    NewtonMeasure                 measured;
    TrilinosWrappers::MPI::Vector update;
    if (!measure_iterate(progress, measured) ||
        !newton_direction(stats, progress, measured, update))
      return false;
    // the Dirichlet increment (zero in the update's constrained rows)
    TrilinosWrappers::MPI::Vector increment(locally_owned, mpi_communicator);
    increment = dirichlet_increment;
    update += increment;
    // the predictor step is taken whole: it carries the boundary data
    advance(progress, update, measured.residual, 0);
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::measure_iterate(NewtonProgress &progress, NewtonMeasure &measured)
  {
    if (!inadmissible_state.empty())
      {
        pcout << "  Newton: " << inadmissible_state << "\n";
        return false;
      }
    measured.residual = residual_norm();
    if (!std::isfinite(measured.residual))
      {
        pcout << "  Newton: the residual is not finite\n";
        return false;
      }
    measured.scaled  = scaled_residual().largest();
    measured.measure = solver_parameters.newton_criterion == Parameters::ResidualCriterion::scaled
                           ? measured.scaled
                           : measured.residual;
    if (progress.iteration == 0)
      progress.first_measure = measured.measure;
    if (output_parameters.log_newton)
      log_iterate(progress.iteration);
    measured.tolerance =
        solver_parameters.newton_tolerance *
        (solver_parameters.newton_criterion == Parameters::ResidualCriterion::relative
             ? progress.first_measure
             : 1.);
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::newton_direction(const StepStatistics          &stats,
                                        NewtonProgress                &progress,
                                        const NewtonMeasure           &measured,
                                        TrilinosWrappers::MPI::Vector &update)
  {
    if (measured.measure > 0.)
      progress.needed_reduction = measured.tolerance / measured.measure;
    return may_iterate(stats, progress, measured) && solve_for_update(progress, update);
  }

  template <int dim>
  bool
  ContactProblem<dim>::may_iterate(const StepStatistics &stats,
                                   const NewtonProgress &progress,
                                   const NewtonMeasure  &measured)
  {
    const unsigned int iteration = progress.iteration;
    if (iteration == solver_parameters.newton_max_iterations)
      {
        pcout << "  Newton: residual " << measured.residual << ' ' << force_unit(false) << " ("
              << measured.measure << " against the criterion's tolerance " << measured.tolerance
              << ") after " << iteration
              << " iterations (Nonlinear solver/Newton/Maximum iterations)\n";
        return false;
      }
    if (stats.newton_iterations + iteration >= solver_parameters.max_newton_per_step)
      {
        pcout << "  Newton: " << stats.newton_iterations + iteration
              << " iterations in this load step (Nonlinear solver/Maximum Newton iterations "
                 "per load step)\n";
        return false;
      }
    // nothing in contact and a rigid motion free: the system is singular,
    // and no smaller load step makes it less so
    if (!free_rigid_motions.empty() && points_in_contact() == 0)
      {
        unrecoverable_failure =
            "the body is not supported: no contact point is in contact (the loads pull it off "
            "the obstacle) and the Dirichlet conditions leave " +
            free_rigid_motions +
            " free. Hold it by a prescribed displacement, or load it towards the obstacle";
        pcout << "  Newton: " << unrecoverable_failure << ".\n";
        return false;
      }
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::solve_for_update(NewtonProgress                &progress,
                                        TrilinosWrappers::MPI::Vector &update)
  {
    if (progress.newton_decides_statuses)
      progress.watch.seen.push_back(point_statuses());
    if (!progress.jacobian_current)
      assemble_newton_system(true);
    update.reinit(locally_owned, mpi_communicator);
    system_rhs *= -1.;
    bool solved = false;
    {
      TimerOutput::Scope scope(timer, "linear solve");
      if (iterative_solver)
        {
          // a tenth of the reduction that meets the Newton tolerance now, or
          // Eisenstat–Walker's forcing term
          const double maximum = linear_solver_parameters.maximum_forcing_term;
          double       forcing = 0.1 * progress.needed_reduction;
          if (linear_solver_parameters.eisenstat_walker)
            forcing = eisenstat_walker_forcing(residual_norm(),
                                               progress.previous_residual,
                                               progress.forcing_term,
                                               progress.iteration == 0,
                                               maximum);
          forcing               = std::clamp(forcing, 1e-10, maximum);
          progress.forcing_term = forcing;
          solved                = solve_by_gmres(*iterative_solver,
                                  system_matrix,
                                  update,
                                  system_rhs,
                                  residual_scaling,
                                  forcing,
                                  work,
                                  pcout);
        }
      if (!solved)
        solved = direct_solver->solve(system_matrix, update, system_rhs);
    }
    ++work.newton_iterations;
    if (!direct_solver->last_retry().empty())
      pcout << "  Newton: " << direct_solver->last_retry() << "\n";
    if (!solved)
      {
        const std::string &error = direct_solver->last_error();
        pcout << "  Newton: the linear solver failed: " << error << ".\n";
        // a smaller load step has the same matrix size and structure
        if (error.find("memory") != std::string::npos ||
            error.find("work space") != std::string::npos)
          unrecoverable_failure = "the linear solver failed: " + error;
        if (error.find("singular") == std::string::npos)
          return false;
      }
    std::string singular = "the linear solver found the matrix singular";
    if (solved)
      {
        newton_constraints.distribute(update);
        singular =
            bounds.implausible(update, locally_owned_u, "the Newton update", mpi_communicator);
      }
    if (!singular.empty())
      {
        if (start_holding_contact())
          {
            assemble_newton_system(true);
            const bool repeated                = solve_for_update(progress, update);
            contact_start.provisional_pressure = 0.;
            contact_start.approach_gap         = 0.;
            return repeated;
          }
        if (!fold_friction_for_slipping_contact())
          report_near_singular(singular);
        return false;
      }
    // the body has been lowered by this solve: the gaps are its own now
    contact_start.approach_gap = 0.;
    if (solver_parameters.adaptive_stopping)
      progress.update_energy = displacement_energy(update);
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::start_holding_contact()
  {
    // nothing touches: the contact starts at the points nearest to the partner
    if (points_in_contact() == 0)
      {
        if (contact_start.approach_used)
          return false;
        close_nearest_points();
        return points_in_contact() > 0;
      }
    // Points in contact with a zero threshold s = μ λ_n hold nothing
    // tangentially (the step's first friction iteration is frictionless): for
    // one solve they see the mean pressure the loads imply, total applied
    // force over the area in contact (or 1e-6 E where the loads are
    // prescribed displacements), so that they stick; the loops then take s
    // from λ_n. (Conditions that keep their own thresholds, the weighted
    // nodes' s_j, would not see those set at the points.)
    if (contact_start.provisional_used || conditions->keeps_own_thresholds() ||
        !any_pressure_dependent_threshold())
      return false;
    const ContactCensus census = contact_census();
    if (census.without_threshold < census.in_contact || census.area <= 0.)
      return false;
    const double area = census.area;
    double       load = 0.;
    for (const auto i : locally_owned_u)
      load += std::abs(external_force(i));
    load                               = Utilities::MPI::sum(load, mpi_communicator);
    contact_start.provisional_used     = true;
    contact_start.provisional_pressure = std::max(load / area, 1e6 * negligible_pressure);
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &) {
      if (state.in_contact)
        state.friction_threshold =
            friction_law_of(state).threshold(contact_start.provisional_pressure);
    });
    pcout << "  the points in contact hold nothing tangentially (their friction threshold mu "
             "lambda_n is still zero): for one solve they see the pressure "
          << contact_start.provisional_pressure << " MPa (the loads over the area in contact)\n";
    return true;
  }

  template <int dim>
  void
  ContactProblem<dim>::report_near_singular(const std::string &symptom)
  {
    pcout << "  Newton: " << symptom << ": the Newton system is singular or nearly so.";
    // points in contact whose friction threshold is still zero hold nothing
    // tangentially: the first friction iteration of a step is frictionless
    const ContactCensus census = contact_census();
    if (census.without_threshold > 0)
      pcout << " " << census.without_threshold
            << " contact points in contact have a zero friction threshold (s = mu lambda_n with "
               "lambda_n not yet known: the step's first friction iteration is frictionless), "
               "so friction holds nothing tangentially there: a body held sideways only by "
               "friction needs another support along the contact in its first load step (a "
               "soft Spring, or a prescribed displacement).";
    if (!free_rigid_motions.empty())
      pcout << " The supports leave " << free_rigid_motions
            << " free, which only the contact can hold; " << census.in_contact
            << " contact points are in contact at this iterate (a contact that has not started, "
               "or that the loads open, holds nothing).";
    // a slipping point's traction is μ λ_n along the slip, whatever the
    // motion along the contact: if all slip, nothing holds that motion
    if (census.in_contact > 0 && census.slipping == census.in_contact &&
        census.without_threshold < census.in_contact)
      pcout << " Every point in contact slips, so friction holds no motion along the contact: "
               "where the supports leave such a motion free, the tangential loads exceed what "
               "friction can hold (the friction coefficient times the normal force) and no "
               "quasi-static equilibrium exists; lower the tangential load or hold the body "
               "along the contact.";
    pcout << " Usual causes: a rigid-body motion the boundary conditions leave free (a rigid "
             "plate or a body held only by a frictionless contact, pushed along the contact); "
             "a sticking contact point whose tangential displacement is prescribed (a Dirichlet "
             "condition on a node of the contact boundary, with friction: its friction "
             "multiplier is then undetermined, and `Linear solver/Null pivot detection = true` "
             "picks one of the equivalent values); a pair that violates the inf-sup condition "
             "(Q1/P2).\n";
  }

  template <int dim>
  typename ContactProblem<dim>::ContactCensus
  ContactProblem<dim>::contact_census()
  {
    ContactCensus census;
    const bool    friction = any_friction();
    for_each_contact_point([&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
      if (!state.in_contact)
        return;
      ++census.in_contact;
      census.area += k.JxW;
      census.without_threshold += friction && state.friction_threshold <= 0.;
      census.slipping += point_response(state, k).status() == Contact::Status::slip;
    });
    census.in_contact        = Utilities::MPI::sum(census.in_contact, mpi_communicator);
    census.slipping          = Utilities::MPI::sum(census.slipping, mpi_communicator);
    census.without_threshold = Utilities::MPI::sum(census.without_threshold, mpi_communicator);
    census.area              = Utilities::MPI::sum(census.area, mpi_communicator);
    return census;
  }

  template <int dim>
  bool
  ContactProblem<dim>::fold_friction_for_slipping_contact()
  {
    // Seed §2.2's friction loop solves a Tresca problem per iteration: with
    // thresholds s too small for the tangential loads (s = μ λ_n of an
    // earlier iterate, or the provisional pressure over an area the loads
    // since reduced) every point slips and, in 2D or under a slip direction
    // shared by all points, nothing resists the motion along the contact.
    // Coulomb's s = μ λ_n grows with the pressure that the same loads
    // produce: the generalized Newton, which linearises it (seed §2.3), finds
    // the stick zone the fixed s cannot.
    if (contact_start.friction_folded || loops.linearised(Loop::friction) ||
        !any_pressure_dependent_threshold())
      return false;
    const ContactCensus census = contact_census();
    if (census.in_contact == 0 || census.slipping < census.in_contact)
      return false;
    contact_start.fold_friction = true;
    pcout << "  friction loop: every one of the " << census.in_contact
          << " points in contact slips under this iteration's fixed friction thresholds and the "
             "Newton system is singular (nothing holds the motion along the contact); the "
             "step is repeated with the friction threshold folded into the generalized Newton\n";
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::plausible_converged_state() const
  {
    const std::string implausible =
        bounds.implausible(solution, locally_owned_u, "the converged state", mpi_communicator);
    if (!implausible.empty())
      pcout << "  " << implausible << ": the loops converged to a state no quasi-static load "
            << "step reaches, which is not accepted\n";
    return implausible.empty();
  }

  template <int dim>
  double
  ContactProblem<dim>::displacement_energy(const TrilinosWrappers::MPI::Vector &update) const
  {
    // (δuᵀ K δu)^½ with the multiplier rows of δ left out: the tangent's
    // energy of the displacement part (the matrix of the last solve)
    TrilinosWrappers::MPI::Vector displacement(locally_owned, mpi_communicator);
    TrilinosWrappers::MPI::Vector product(locally_owned, mpi_communicator);
    for (const auto index : locally_owned_u)
      displacement(index) = update(index);
    displacement.compress(VectorOperation::insert);
    system_matrix.vmult(product, displacement);
    return std::sqrt(std::abs(displacement * product));
  }

  template <int dim>
  bool
  ContactProblem<dim>::adaptive_stop(NewtonProgress &progress, const double scaled_residual)
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
    if (!solver_parameters.adaptive_stopping || progress.iteration == 0 ||
        !std::isfinite(progress.update_energy) ||
        !below_discretisation_error(progress.update_energy, scaled_residual))
      return false;
    if (output_parameters.log_newton)
      pcout << "    Newton stops adaptively: last update " << progress.update_energy
            << " sqrt(N mm), scaled residual " << scaled_residual
            << ", estimated discretisation error " << last_estimate.error
            << " sqrt(N mm), relative " << last_estimate.relative() << "\n";
    return true;
  }

  template <int dim>
  bool
  ContactProblem<dim>::below_discretisation_error(const double change_energy,
                                                  const double relative_change)
  {
    // No estimate is made while the change is above twice what the last
    // estimate (of any loop, on this mesh or an earlier one) allows: the
    // estimate moves far less than the changes. Where it grew since, a check
    // that might have stopped is skipped: fewer early stops, never a wrong one.
    const double fraction = solver_parameters.adaptive_fraction;
    if (last_estimate.error > 0. && (change_energy > 2. * fraction * last_estimate.error ||
                                     relative_change > 2. * fraction * last_estimate.relative()))
      return false;
    last_estimate = estimated_energy_error();
    return change_energy <= fraction * last_estimate.error &&
           relative_change <= fraction * last_estimate.relative();
  }

  template <int dim>
  void
  ContactProblem<dim>::log_iterate(const unsigned int iteration) const
  {
    const ScaledResidual scaled = scaled_residual();
    std::ostringstream   line;
    line << std::setprecision(6) << "    Newton " << iteration << ": residual " << residual_norm()
         << ' ' << force_unit(false) << "; scaled: force " << scaled.force << ", gap " << scaled.gap
         << ", slip " << scaled.slip << "\n";
    pcout << line.str();
  }

  // Explicit instantiation of the members defined in this file (the class
  // itself is instantiated once, in contact_problem.cc).
#define SL_INSTANTIATE(dim)                                                                       \
  template std::vector<unsigned char> ContactProblem<dim>::point_statuses();                      \
  template bool                       ContactProblem<dim>::newton_loop(                           \
      StepStatistics &, unsigned int, unsigned int, unsigned int);          \
  template bool   ContactProblem<dim>::predictor_step(StepStatistics &, NewtonProgress &);        \
  template bool   ContactProblem<dim>::measure_iterate(NewtonProgress &, NewtonMeasure &);        \
  template bool   ContactProblem<dim>::adaptive_stop(NewtonProgress &, double);                   \
  template bool   ContactProblem<dim>::below_discretisation_error(double, double);                \
  template double ContactProblem<dim>::displacement_energy(const TrilinosWrappers::MPI::Vector &) \
      const;                                                                                      \
  template bool ContactProblem<dim>::newton_direction(const StepStatistics &,                     \
                                                      NewtonProgress &,                           \
                                                      const NewtonMeasure &,                      \
                                                      TrilinosWrappers::MPI::Vector &);           \
  template bool ContactProblem<dim>::may_iterate(                                                 \
      const StepStatistics &, const NewtonProgress &, const NewtonMeasure &);                     \
  template bool ContactProblem<dim>::solve_for_update(NewtonProgress &,                           \
                                                      TrilinosWrappers::MPI::Vector &);           \
  template bool ContactProblem<dim>::start_holding_contact();                                     \
  template typename ContactProblem<dim>::ContactCensus ContactProblem<dim>::contact_census();     \
  template bool ContactProblem<dim>::fold_friction_for_slipping_contact();                        \
  template void ContactProblem<dim>::report_near_singular(const std::string &);                   \
  template bool ContactProblem<dim>::plausible_converged_state() const;                           \
  template void ContactProblem<dim>::log_iterate(unsigned int) const;

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
