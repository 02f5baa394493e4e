#pragma once

#include <stabilized_lagrangian/contact/contact_conditions.h>

namespace StabilizedLagrangian
{
  /**
   * @brief The multiplier DoFs of one face grouped by node: per base DoF of
   * the multiplier element, the DoFs @p global (of the element's local indices
   * @p local) of λ_n, then Λ_α.
   */
  template <int dim>
  std::map<unsigned int, std::vector<types::global_dof_index>>
  multiplier_nodes(const FiniteElement<dim>                   &fe_m,
                   const std::vector<unsigned int>            &local,
                   const std::vector<types::global_dof_index> &global);

  /**
   * @brief `Contact/Complementarity = weighted` (doc/formulation.md, "Weighted
   * complementarity"): the contact and friction conditions hold once per
   * multiplier node j, on the weighted gap g_j = ∫ψ_j g_n / D_j and slip
   * Δs_j = ∫ψ_j Δs / D_j, D_j = ∫ψ_j, as in mortar methods; the displacement
   * sees the multiplier field itself. Each contact point carries a copy of its
   * nearest node's status and threshold, for the output, the counts and the
   * error estimate.
   */
  template <int dim> class WeightedConditions : public ContactConditions<dim>
  {
  public:
    using ContactConditions<dim>::ContactConditions;

    /** The nodes' s_j (`thresholds`); the points carry copies. */
    bool
    keeps_own_thresholds() const override
    {
      return true;
    }
    /** Size the nodal vectors, find the nodes of this rank's contact faces. */
    void
    setup() override;
    unsigned int
    update_statuses() override;
    double
    update_thresholds() override;
    std::vector<unsigned char>
    contact_statuses() const override;
    std::vector<unsigned char>
    statuses() override;
    /** The least weighted gap ∫ψ_j g_n / ∫ψ_j of the nodes. */
    double
    least_gap(const double nearest_point) override;
    void
    close_nearest(const double nearest, const double touching) override;
    PointRefresh
    prepare_assembly(const PointRefresh &refresh) override;
    void
    prepare_sampling() override;
    void
    reinit_face(const FaceEvaluator<dim> &evaluator) override;
    void
    add_point(internal::ContactFaceSystem<dim> &local,
              const ContactPointState<dim>     &state,
              const ContactKinematics<dim>     &k,
              const bool                        assemble_matrix,
              const bool                        linearise_geometry) const override;
    const Contact::PointResponse<dim - 1> *
    response_at(const FaceEvaluator<dim> &evaluator, const unsigned int q) const override;
    void
    statistics(StepStatistics                 &stats,
               Contact::FrictionLawCheck<dim> &check,
               std::vector<Point<dim>>        &active_set) override;
    std::unique_ptr<ContactConditions<dim>>
    copy() const override
    {
      return std::make_unique<WeightedConditions<dim>>(*this);
    }
    /** Back to the nodal vectors of @p copy, a copy of these conditions on the same mesh. */
    void
    restore(const ContactConditions<dim> &copy) override;
    std::vector<double>
    owned_states() const override;
    void
    restore_states(const std::vector<double> &values) override;
    std::size_t
    n_state_values() const override
    {
      return 2 * owned_nodes.size();
    }
    unsigned int
    freeze(const std::function<bool(unsigned int)> &in_contact, const double threshold) override;

  private:
    /** ghosted vectors in the solution's layout, set on the multiplier DoFs */
    TrilinosWrappers::MPI::Vector weights; ///< D_j = ∫ψ_j at every multiplier DoF
    TrilinosWrappers::MPI::Vector integrals; ///< ∫ψ_j g_n at λ_n DoFs, ∫ψ_j Δs_α at Λ_α DoFs
    TrilinosWrappers::MPI::Vector status;     ///< χ_j, 1 or 0, at the λ_n DoFs (status loop)
    TrilinosWrappers::MPI::Vector thresholds; ///< s_j at the λ_n DoFs (friction loop)
    using Nodes =
        std::vector<std::pair<types::global_dof_index, std::vector<types::global_dof_index>>>;
    /** the owned nodes: the λ_n DoF, and the Λ DoFs of the same node */
    Nodes owned_nodes;
    /** likewise, every node of this rank's contact faces (owned and ghost) */
    Nodes nodes;
    /** The response of every node of this rank's contact faces, by its λ_n DoF. */
    std::map<types::global_dof_index, Contact::PointResponse<dim - 1>> responses;
    /** per multiplier of the face of the last reinit_face(), its node's response */
    std::vector<const Contact::PointResponse<dim - 1> *> face_nodes;

    /** D_j, ∫ψ_j g_n and ∫ψ_j Δs at the iterate (the pairing refreshed with @p pairing). */
    void
    update_integrals(const bool pairing);
    /**
     * The status χ_j of every node at the iterate (the integrals recomputed
     * unless @p integrals_current); returns how many changed.
     */
    unsigned int
    update_nodal_statuses(const bool integrals_current);
    /** The threshold s_j of every node; returns the largest change against the largest s_j. */
    double
    update_nodal_thresholds();
    /** The stabilized Lagrangian of a node on its weighted gap and slip, with its χ_j and s_j. */
    Contact::PointResponse<dim - 1>
    nodal_response(const types::global_dof_index               node,
                   const std::vector<types::global_dof_index> &semi_dofs) const;
    /** Every node's response into `responses`, once (an assembly, the output, the statistics). */
    void
    compute_responses();
    /** The index in FaceEvaluator::m_dofs of the λ_n with the largest ψ_j at point @p q. */
    unsigned int
    nearest_multiplier(const FaceEvaluator<dim> &evaluator, unsigned int q) const;
    /** Each contact point takes the status and threshold of its nearest node. */
    void
    copy_states_to_points();
  };
} // namespace StabilizedLagrangian
