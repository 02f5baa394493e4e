#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/friction_law.h>
#include <stabilized_lagrangian/contact/friction_law_check.h>
#include <stabilized_lagrangian/contact/stabilized_lagrangian.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>
#include <stabilized_lagrangian/solver/contact_face_system.h>
#include <stabilized_lagrangian/solver/loop_policy.h>

#include <functional>
#include <map>
#include <memory>
#include <vector>

/**
 * @file
 * The contact and friction conditions on Γc (doc/formulation.md, "Weighted
 * complementarity"): where the stabilized Lagrangian of seed eq. (7) holds —
 * at every contact point (pointwise, the seed's) or once per multiplier node on
 * the weighted gap and slip (weighted, as in mortar methods). The loops, the
 * Newton assembly, the output, the statistics and the checkpoint ask a
 * ContactConditions and never which one it is; make_contact_conditions() is
 * the one place that knows both.
 */

namespace StabilizedLagrangian
{
  /**
   * @brief What the conditions ask of the contact points: the one evaluation
   * of a point's state at the iterate and the law at a point.
   */
  template <int dim> class ContactPointLaw
  {
  public:
    virtual ~ContactPointLaw() = default;
    /**
     * Evaluate the state of a contact point at the iterate: its pairing, then
     * its friction threshold and status as @p what names.
     */
    virtual void
    evaluate_point_state(ContactPointState<dim> &state,
                         ContactKinematics<dim> &k,
                         const PointRefresh     &what) const = 0;
    /** The point-wise stabilized Lagrangian with the status and threshold of @p state. */
    virtual Contact::PointResponse<dim - 1>
    point_response(const ContactPointState<dim> &state, const ContactKinematics<dim> &k) const = 0;
    /** The gap the status test sees: 0 within the touching distance of zero. */
    virtual double
    status_gap(const double gap) const = 0;
    /** The pressure the friction threshold sees: λ_n, or 0 below the negligible pressure. */
    virtual double
    threshold_pressure(double contact_pressure) const = 0;
    /** The friction law of the point's zone. */
    virtual const FrictionLaws::Interface &
    friction_law_of(const ContactPointState<dim> &state) const = 0;
  };

  /**
   * @brief What the conditions read and write: the contact faces and their
   * points (owned by the problem), the iterate, the parallel layout, the
   * stabilization parameters and the loop policy.
   */
  template <int dim> struct ContactConditionsData
  {
    const ContactSpaces<dim>            &spaces;
    const Quadrature<dim - 1>           &contact_quadrature;
    const std::vector<ContactFace<dim>> &faces;
    std::vector<ContactPointState<dim>> &states;
    /** relevant: the iterate */
    const TrilinosWrappers::MPI::Vector &ghosted_solution;
    const IndexSet                      &locally_owned;
    const IndexSet                      &locally_relevant;
    const MPI_Comm                      &communicator;
    const ContactPointLaw<dim>          &law;
    /** the default friction law (the weighted conditions have no zones) */
    const std::unique_ptr<FrictionLaws::Interface> &friction_law;
    const double                                   &r_n;
    const double                                   &r_t;
    const LoopPolicy                               &loops;
    const double                                   &negligible_pressure;
    /** the number of contact zones (`Contact/Zone <name>`), for their forces */
    std::function<unsigned int()> n_zones;
    /**
     * Call f(dofs, face) for each contact face of the non-artificial cells,
     * with the multiplier DoFs of its cell (multiplier numbering).
     */
    std::function<void(
        const std::function<void(const std::vector<types::global_dof_index> &, unsigned int)> &)>
        for_each_multiplier_face;
  };

  /**
   * @brief The contact and friction conditions on Γc, their frozen statuses
   * and thresholds, and their part in the Newton system.
   */
  template <int dim> class ContactConditions
  {
  public:
    explicit ContactConditions(const ContactConditionsData<dim> &data)
        : data(data)
    {
    }
    virtual ~ContactConditions() = default;

    /**
     * Whether the Newton system sees friction thresholds that the conditions
     * keep themselves (the weighted nodes' s_j), each contact point holding a
     * copy: a threshold written into a point's state is then not seen.
     */
    virtual bool
    keeps_own_thresholds() const = 0;
    /** After the contact points of a new mesh: size the conditions' own state. */
    virtual void
    setup() = 0;
    /** The status loop: every status at the iterate; returns how many changed. */
    virtual unsigned int
    update_statuses() = 0;
    /**
     * The friction loop: every threshold at the iterate; returns the largest
     * change against the largest threshold.
     */
    virtual double
    update_thresholds() = 0;
    /** In contact or not, per owned condition (the status loop's cycles). */
    virtual std::vector<unsigned char>
    contact_statuses() const = 0;
    /** Open, stick or slip per owned condition (the active-set watch). */
    virtual std::vector<unsigned char>
    statuses() = 0;
    /**
     * The least gap of the owned conditions at the iterate, over the ranks (a
     * body put on its partner), where @p nearest_point is the least gap of the
     * contact points, over the ranks.
     */
    virtual double
    least_gap(const double nearest_point) = 0;
    /**
     * A body put on its partner: the conditions whose gap is within
     * @p touching of @p nearest close (after least_gap()).
     */
    virtual void
    close_nearest(const double nearest, const double touching) = 0;

    /**
     * Before an assembly: refresh what the iterate refreshes (@p refresh);
     * returns what is left for each point to refresh.
     */
    virtual PointRefresh
    prepare_assembly(const PointRefresh &refresh) = 0;
    /** Before the output or the statistics samples the faces: the responses at the iterate. */
    virtual void
    prepare_sampling() = 0;
    /** Set to the face @p evaluator was last set to (after prepare_assembly() or _sampling()). */
    virtual void
    reinit_face(const FaceEvaluator<dim> &evaluator) = 0;
    /** Add the contact terms of point @p k of the face to its local system. */
    virtual void
    add_point(internal::ContactFaceSystem<dim> &local,
              const ContactPointState<dim>     &state,
              const ContactKinematics<dim>     &k,
              const bool                        assemble_matrix,
              const bool                        linearise_geometry) const = 0;
    /**
     * The response that holds at point @p q of the face (the nearest node's);
     * null where each point holds its own.
     */
    virtual const Contact::PointResponse<dim - 1> *
    response_at(const FaceEvaluator<dim> &evaluator, const unsigned int q) const = 0;

    /**
     * The contact counts and forces of the converged iterate into @p stats,
     * the points in contact into @p check and @p active_set.
     */
    virtual void
    statistics(StepStatistics                 &stats,
               Contact::FrictionLawCheck<dim> &check,
               std::vector<Point<dim>>        &active_set) = 0;

    /** A copy of the conditions' state (the step-cut snapshot); restore() puts it back. */
    virtual std::unique_ptr<ContactConditions<dim>>
    copy() const = 0;
    virtual void
    restore(const ContactConditions<dim> &copy) = 0;
    /** The owned conditions' frozen state, for a checkpoint; and back (same size). */
    virtual std::vector<double>
    owned_states() const = 0;
    virtual void
    restore_states(const std::vector<double> &values) = 0;
    /** The size of owned_states(). */
    virtual std::size_t
    n_state_values() const = 0;
    /**
     * Freeze the status of the k-th owned condition to @p in_contact(k) and
     * every threshold to @p threshold (tests); returns the number of owned
     * conditions, 0 where the points hold theirs.
     */
    virtual unsigned int
    freeze(const std::function<bool(unsigned int)> &in_contact, const double threshold) = 0;

  protected:
    ContactConditionsData<dim> data;
    /**
     * The counts of this rank's conditions (all, in contact, stick, slip) and
     * its contact forces (total and tangential vectors) summed over the ranks
     * into @p stats.
     */
    void
    gather_totals(StepStatistics       &stats,
                  const unsigned int    counts[4],
                  const double          normal_force,
                  const Tensor<1, dim> &total_force,
                  const Tensor<1, dim> &tangential_force) const;
    /** Call f(state, kinematics) at every owned point, its state evaluated as @p what names. */
    void
    for_each_point(const PointRefresh                                         &what,
                   const std::function<void(ContactPointState<dim>       &state,
                                            const ContactKinematics<dim> &k)> &f);
    /**
     * Call f(before, state, kinematics) at every owned point, its state
     * evaluated as @p what names, with its state before (a loop's change).
     */
    void
    refresh_points(const PointRefresh                                         &what,
                   const std::function<void(const ContactPointState<dim> &before,
                                            ContactPointState<dim>       &state,
                                            const ContactKinematics<dim> &k)> &f);

  private:
    /** Call f(state, kinematics) at every owned point, nothing evaluated. */
    void
    visit_points(
        const std::function<void(ContactPointState<dim> &state, ContactKinematics<dim> &k)> &f);
  };

  /**
   * @brief The conditions of `Contact/Complementarity` (pointwise or weighted,
   * after `automatic` has chosen): the one place that names them.
   */
  template <int dim>
  std::unique_ptr<ContactConditions<dim>>
  make_contact_conditions(const bool weighted, const ContactConditionsData<dim> &data);
} // namespace StabilizedLagrangian
