#pragma once

#include <stabilized_lagrangian/contact/contact_conditions.h>

namespace StabilizedLagrangian
{
  /**
   * @brief `Contact/Complementarity = pointwise`, the seed's: the conditions
   * hold at every contact point, each with its own frozen status and threshold
   * (ContactPointState).
   */
  template <int dim> class PointwiseConditions : public ContactConditions<dim>
  {
  public:
    using ContactConditions<dim>::ContactConditions;

    /** Each point's own threshold is the one the Newton system sees. */
    bool
    keeps_own_thresholds() const override
    {
      return false;
    }
    void
    setup() override
    {
    }
    unsigned int
    update_statuses() override;
    double
    update_thresholds() override;
    std::vector<unsigned char>
    contact_statuses() const override;
    std::vector<unsigned char>
    statuses() override;
    /** Each point holds its own conditions: the least gap of the points. */
    double
    least_gap(const double nearest_point) override
    {
      return nearest_point;
    }
    void
    close_nearest(const double nearest, const double touching) override;
    PointRefresh
    prepare_assembly(const PointRefresh &refresh) override
    {
      return refresh;
    }
    void
    prepare_sampling() override
    {
    }
    void
    reinit_face(const FaceEvaluator<dim> &) override
    {
    }
    void
    add_point(internal::ContactFaceSystem<dim> &local,
              const ContactPointState<dim>     &state,
              const ContactKinematics<dim>     &k,
              const bool                        assemble_matrix,
              const bool                        linearise_geometry) const override;
    const Contact::PointResponse<dim - 1> *
    response_at(const FaceEvaluator<dim> &, const unsigned int) const override
    {
      return nullptr;
    }
    void
    statistics(StepStatistics                 &stats,
               Contact::FrictionLawCheck<dim> &check,
               std::vector<Point<dim>>        &active_set) override;
    std::unique_ptr<ContactConditions<dim>>
    copy() const override
    {
      return std::make_unique<PointwiseConditions<dim>>(*this);
    }
    /** The points' states are the problem's: nothing of its own. */
    void
    restore(const ContactConditions<dim> &) override
    {
    }
    std::vector<double>
    owned_states() const override
    {
      return {};
    }
    void
    restore_states(const std::vector<double> &values) override;
    std::size_t
    n_state_values() const override
    {
      return 0;
    }
    unsigned int
    freeze(const std::function<bool(unsigned int)> &, const double) override
    {
      return 0;
    }
  };
} // namespace StabilizedLagrangian
