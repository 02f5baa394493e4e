#include <stabilized_lagrangian/contact/contact_conditions.h>
#include <stabilized_lagrangian/contact/pointwise_conditions.h>
#include <stabilized_lagrangian/contact/weighted_conditions.h>

namespace StabilizedLagrangian
{
  template <int dim>
  void
  ContactConditions<dim>::visit_points(
      const std::function<void(ContactPointState<dim> &state, ContactKinematics<dim> &k)> &f)
  {
    FaceEvaluator<dim> evaluator(data.spaces, data.contact_quadrature);
    for (const auto &face : data.faces)
      {
        evaluator.reinit(face, data.ghosted_solution);
        for (unsigned int q = 0; q < evaluator.n_points(); ++q)
          {
            ContactKinematics<dim> k = evaluator.kinematics(q);
            f(data.states[face.first_point + q], k);
          }
      }
  }

  template <int dim>
  void
  ContactConditions<dim>::for_each_point(
      const PointRefresh &what,
      const std::function<void(ContactPointState<dim> &state, const ContactKinematics<dim> &k)> &f)
  {
    visit_points([&](ContactPointState<dim> &state, ContactKinematics<dim> &k) {
      data.law.evaluate_point_state(state, k, what);
      f(state, k);
    });
  }

  template <int dim>
  void
  ContactConditions<dim>::refresh_points(
      const PointRefresh                                         &what,
      const std::function<void(const ContactPointState<dim> &before,
                               ContactPointState<dim>       &state,
                               const ContactKinematics<dim> &k)> &f)
  {
    visit_points([&](ContactPointState<dim> &state, ContactKinematics<dim> &k) {
      const ContactPointState<dim> before = state;
      data.law.evaluate_point_state(state, k, what);
      f(before, state, k);
    });
  }

  template <int dim>
  void
  ContactConditions<dim>::gather_totals(StepStatistics       &stats,
                                        const unsigned int    counts[4],
                                        const double          normal_force,
                                        const Tensor<1, dim> &total_force,
                                        const Tensor<1, dim> &tangential_force) const
  {
    const MPI_Comm &communicator    = data.communicator;
    stats.contact_points            = Utilities::MPI::sum(counts[0], communicator);
    stats.points_in_contact         = Utilities::MPI::sum(counts[1], communicator);
    stats.points_stick              = Utilities::MPI::sum(counts[2], communicator);
    stats.points_slip               = Utilities::MPI::sum(counts[3], communicator);
    stats.normal_force              = Utilities::MPI::sum(normal_force, communicator);
    const Tensor<1, dim> total      = Utilities::MPI::sum(total_force, communicator);
    const Tensor<1, dim> tangential = Utilities::MPI::sum(tangential_force, communicator);
    stats.tangential_force          = tangential.norm();
    for (unsigned int d = 0; d < dim; ++d)
      stats.contact_force[d] = total[d];
  }

  template <int dim>
  std::unique_ptr<ContactConditions<dim>>
  make_contact_conditions(const bool weighted, const ContactConditionsData<dim> &data)
  {
    if (weighted)
      return std::make_unique<WeightedConditions<dim>>(data);
    return std::make_unique<PointwiseConditions<dim>>(data);
  }

  template class ContactConditions<2>;
  template class ContactConditions<3>;
  template std::unique_ptr<ContactConditions<2>>
  make_contact_conditions(const bool, const ContactConditionsData<2> &);
  template std::unique_ptr<ContactConditions<3>>
  make_contact_conditions(const bool, const ContactConditionsData<3> &);
} // namespace StabilizedLagrangian
