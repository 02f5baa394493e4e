// What the Newton iteration does when its system is singular or nearly so
// (doc/formulation.md, "What a converged state must satisfy"): start the
// contact that would hold the body, fold the friction threshold into the
// generalized Newton when every point slips, or say why no smaller load step
// helps.

#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/solver/newton_solver.h>

#include <algorithm>
#include <cmath>

namespace StabilizedLagrangian
{
  template <int dim>
  bool
  NewtonSolver<dim>::start_holding_contact()
  {
    // nothing touches: the contact starts at the points nearest to the partner
    if (problem.points_in_contact() == 0)
      {
        if (problem.contact_start.approach_used)
          return false;
        problem.close_nearest_points();
        return problem.points_in_contact() > 0;
      }
    // Points in contact with a zero threshold s = μ λ_n hold nothing
    // tangentially (the step's first friction iteration is frictionless): for
    // one solve they see the mean pressure the loads imply, total applied
    // force over the area in contact (or 1e-6 E where the loads are
    // prescribed displacements), so that they stick; the loops then take s
    // from λ_n. (Conditions that keep their own thresholds, the weighted
    // nodes' s_j, would not see those set at the points.)
    if (problem.contact_start.provisional_used ||
        problem.contact.conditions().keeps_own_thresholds() ||
        !problem.any_pressure_dependent_threshold())
      return false;
    const ContactCensus census = contact_census();
    if (census.without_threshold < census.in_contact || census.area <= 0.)
      return false;
    const double area = census.area;
    double       load = 0.;
    for (const auto i : problem.locally_owned_u)
      load += std::abs(problem.external_force(i));
    load                                   = Utilities::MPI::sum(load, problem.communicator);
    problem.contact_start.provisional_used = true;
    problem.contact_start.provisional_pressure =
        std::max(load / area, 1e6 * problem.negligible_pressure);
    problem.for_each_contact_point(
        [&](ContactPointState<dim> &state, const ContactKinematics<dim> &) {
          if (state.in_contact)
            state.friction_threshold = problem.law.friction_law_of(state).threshold(
                problem.contact_start.provisional_pressure);
        });
    problem.pcout
        << "  the points in contact hold nothing tangentially (their friction threshold mu "
           "lambda_n is still zero): for one solve they see the pressure "
        << problem.contact_start.provisional_pressure
        << " MPa (the loads over the area in contact)\n";
    return true;
  }

  template <int dim>
  void
  NewtonSolver<dim>::report_near_singular(const std::string &symptom) const
  {
    problem.pcout << "  Newton: " << symptom << ": the Newton system is singular or nearly so.";
    // points in contact whose friction threshold is still zero hold nothing
    // tangentially: the first friction iteration of a step is frictionless
    const ContactCensus census = contact_census();
    if (census.without_threshold > 0)
      problem.pcout
          << " " << census.without_threshold
          << " contact points in contact have a zero friction threshold (s = mu lambda_n with "
             "lambda_n not yet known: the step's first friction iteration is frictionless), "
             "so friction holds nothing tangentially there: a body held sideways only by "
             "friction needs another support along the contact in its first load step (a "
             "soft Spring, or a prescribed displacement).";
    if (!problem.free_rigid_motions.empty())
      problem.pcout
          << " The supports leave " << problem.free_rigid_motions
          << " free, which only the contact can hold; " << census.in_contact
          << " contact points are in contact at this iterate (a contact that has not started, "
             "or that the loads open, holds nothing).";
    // a slipping point's traction is μ λ_n along the slip, whatever the
    // motion along the contact: if all slip, nothing holds that motion
    if (census.in_contact > 0 && census.slipping == census.in_contact &&
        census.without_threshold < census.in_contact)
      problem.pcout
          << " Every point in contact slips, so friction holds no motion along the contact: "
             "where the supports leave such a motion free, the tangential loads exceed what "
             "friction can hold (the friction coefficient times the normal force) and no "
             "quasi-static equilibrium exists; lower the tangential load or hold the body "
             "along the contact.";
    problem.pcout
        << " Usual causes: a rigid-body motion the boundary conditions leave free (a rigid "
           "plate or a body held only by a frictionless contact, pushed along the contact); "
           "a sticking contact point whose tangential displacement is prescribed (a Dirichlet "
           "condition on a node of the contact boundary, with friction: its friction "
           "multiplier is then undetermined, and `Linear solver/Null pivot detection = true` "
           "picks one of the equivalent values); a pair that violates the inf-sup condition "
           "(Q1/P2).\n";
  }

  template <int dim>
  typename NewtonSolver<dim>::ContactCensus
  NewtonSolver<dim>::contact_census() const
  {
    ContactCensus census;
    const bool    friction = problem.any_friction();
    problem.for_each_contact_point(
        [&](ContactPointState<dim> &state, const ContactKinematics<dim> &k) {
          if (!state.in_contact)
            return;
          ++census.in_contact;
          census.area += k.JxW;
          census.without_threshold += friction && state.friction_threshold <= 0.;
          census.slipping += problem.law.point_response(state, k).status() == Contact::Status::slip;
        });
    census.in_contact        = Utilities::MPI::sum(census.in_contact, problem.communicator);
    census.slipping          = Utilities::MPI::sum(census.slipping, problem.communicator);
    census.without_threshold = Utilities::MPI::sum(census.without_threshold, problem.communicator);
    census.area              = Utilities::MPI::sum(census.area, problem.communicator);
    return census;
  }

  template <int dim>
  bool
  NewtonSolver<dim>::fold_friction_for_slipping_contact()
  {
    // Seed §2.2's friction loop solves a Tresca problem per iteration: with
    // thresholds s too small for the tangential loads (s = μ λ_n of an
    // earlier iterate, or the provisional pressure over an area the loads
    // since reduced) every point slips and, in 2D or under a slip direction
    // shared by all points, nothing resists the motion along the contact.
    // Coulomb's s = μ λ_n grows with the pressure that the same loads
    // produce: the generalized Newton, which linearises it (seed §2.3), finds
    // the stick zone the fixed s cannot.
    if (problem.contact_start.friction_folded || problem.loops.linearised(Loop::friction) ||
        !problem.any_pressure_dependent_threshold())
      return false;
    const ContactCensus census = contact_census();
    if (census.in_contact == 0 || census.slipping < census.in_contact)
      return false;
    problem.contact_start.fold_friction = true;
    problem.pcout
        << "  friction loop: every one of the " << census.in_contact
        << " points in contact slips under this iteration's fixed friction thresholds and the "
           "Newton system is singular (nothing holds the motion along the contact); the "
           "step is repeated with the friction threshold folded into the generalized Newton\n";
    return true;
  }

  // Explicit instantiation of the members defined in this file.
#define SL_INSTANTIATE(dim)                                                                     \
  template bool NewtonSolver<dim>::start_holding_contact();                                     \
  template void NewtonSolver<dim>::report_near_singular(const std::string &) const;             \
  template typename NewtonSolver<dim>::ContactCensus NewtonSolver<dim>::contact_census() const; \
  template bool NewtonSolver<dim>::fold_friction_for_slipping_contact();

  SL_INSTANTIATE(2)
  SL_INSTANTIATE(3)
#undef SL_INSTANTIATE
} // namespace StabilizedLagrangian
