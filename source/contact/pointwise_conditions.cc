#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/pointwise_conditions.h>

#include <cmath>

namespace StabilizedLagrangian
{
  template <int dim>
  unsigned int
  PointwiseConditions<dim>::update_statuses()
  {
    unsigned int changes = 0;
    PointRefresh what;
    what.status = true;
    this->refresh_points(what, [&](const auto &before, const auto &state, const auto &) {
      changes += before.in_contact != state.in_contact;
    });
    return Utilities::MPI::sum(changes, this->data.communicator);
  }

  template <int dim>
  double
  PointwiseConditions<dim>::update_thresholds()
  {
    double       max_change = 0., max_threshold = 0.;
    PointRefresh what;
    what.threshold = true;
    this->refresh_points(what, [&](const auto &before, const auto &state, const auto &) {
      const double s = state.friction_threshold;
      max_change     = std::max(max_change, std::abs(s - before.friction_threshold));
      max_threshold  = std::max(max_threshold, s);
    });
    max_change    = Utilities::MPI::max(max_change, this->data.communicator);
    max_threshold = Utilities::MPI::max(max_threshold, this->data.communicator);
    if (max_threshold == 0.)
      return max_change == 0. ? 0. : 1.;
    return max_change / max_threshold;
  }

  template <int dim>
  std::vector<unsigned char>
  PointwiseConditions<dim>::contact_statuses() const
  {
    std::vector<unsigned char> statuses;
    for (const auto &state : this->data.states)
      statuses.push_back(state.in_contact);
    return statuses;
  }

  template <int dim>
  std::vector<unsigned char>
  PointwiseConditions<dim>::statuses()
  {
    std::vector<unsigned char> statuses;
    statuses.reserve(this->data.states.size());
    this->for_each_point(PointRefresh(), [&](const auto &state, const auto &k) {
      statuses.push_back(
          static_cast<unsigned char>(this->data.law.point_response(state, k).status()));
    });
    return statuses;
  }

  template <int dim>
  void
  PointwiseConditions<dim>::close_nearest(const double nearest, const double touching)
  {
    this->for_each_point(PointRefresh(), [&](auto &state, const auto &k) {
      state.in_contact = state.pairing.gap(k.position) <= nearest + touching;
    });
  }

  template <int dim>
  void
  PointwiseConditions<dim>::add_point(internal::ContactFaceSystem<dim> &local,
                                      const ContactPointState<dim>     &state,
                                      const ContactKinematics<dim>     &k,
                                      const bool                        assemble_matrix,
                                      const bool                        linearise_geometry) const
  {
    const auto point = this->data.law.point_response(state, k);
    local.add_residual(point, k.JxW);
    if (assemble_matrix)
      local.add_jacobian(point, state.pairing, k.JxW, linearise_geometry);
  }

  template <int dim>
  void
  PointwiseConditions<dim>::statistics(StepStatistics                 &stats,
                                       Contact::FrictionLawCheck<dim> &check,
                                       std::vector<Point<dim>>        &active_set)
  {
    const MPI_Comm &communicator = this->data.communicator;
    unsigned int    counts[4]    = {0, 0, 0, 0}; // all, in contact, stick, slip
    double          normal_force = 0.;
    Tensor<1, dim>  total_force, tangential_force;
    // per zone (0: the default law's boundaries): normal force, tangential force vector
    const unsigned int          n_zones = this->data.n_zones();
    std::vector<double>         zone_normal(n_zones + 1, 0.);
    std::vector<Tensor<1, dim>> zone_tangential(n_zones + 1);
    this->for_each_point(PointRefresh(), [&](const auto &state, const auto &k) {
      const auto point = this->data.law.point_response(state, k);
      ++counts[0];
      if (point.status() == Contact::Status::open)
        return;
      ++counts[1];
      ++counts[point.status() == Contact::Status::stick ? 2 : 3];
      check.add_point(k.position - k.displacement,
                      point.tangential_traction().norm(),
                      this->data.law.friction_law_of(state).threshold(
                          this->data.law.threshold_pressure(k.contact_pressure)));
      active_set.push_back(k.position - k.displacement);
      const Tensor<1, dim> tangential =
          state.pairing.from_tangential_components(point.tangential_traction());
      normal_force += k.JxW * point.normal_traction();
      total_force += k.JxW * point.normal_traction() * state.pairing.normal;
      tangential_force += k.JxW * tangential;
      zone_normal[state.zone] += k.JxW * point.normal_traction();
      zone_tangential[state.zone] += k.JxW * tangential;
    });
    stats.zone_forces.assign(n_zones, {{0., 0.}});
    for (unsigned int z = 0; z < n_zones; ++z)
      stats.zone_forces[z] = {{Utilities::MPI::sum(zone_normal[z + 1], communicator),
                               Utilities::MPI::sum(zone_tangential[z + 1], communicator).norm()}};
    total_force += tangential_force;
    this->gather_totals(stats, counts, normal_force, total_force, tangential_force);
  }

  template <int dim>
  void
  PointwiseConditions<dim>::restore_states(const std::vector<double> &values)
  {
    AssertThrow(values.empty(), ExcMessage("the checkpoint's contact nodes do not fit this mesh"));
  }

  template class PointwiseConditions<2>;
  template class PointwiseConditions<3>;
} // namespace StabilizedLagrangian
