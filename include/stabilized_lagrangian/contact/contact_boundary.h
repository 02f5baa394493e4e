#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/contact/contact_conditions.h>
#include <stabilized_lagrangian/contact/contact_surface.h>
#include <stabilized_lagrangian/contact/cumulative_slip.h>
#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/contact/stabilized_point_law.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/body_mesh.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/chosen_parameters.h>
#include <stabilized_lagrangian/solver/run_state.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

/**
 * @file
 * Γc on this rank's cells: its faces, the states of their contact points and
 * the contact conditions that hold there (pointwise or weighted).
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The contact boundary Γc of the locally owned cells: its faces
   * (ContactFace, with their segments, consistent nodal weights and dual
   * basis), the frozen state of every contact point of them (pairing,
   * threshold, status) and the contact conditions chosen for them
   * (make_contact_conditions(), the one place that names pointwise and
   * weighted). The problem re-pairs, iterates and assembles through it; no
   * one else holds the points.
   *
   * It reads the discretisation through a View of references, so it follows
   * them as they change (a new mesh, a new partner, the iterate).
   */
  template <int dim> class ContactBoundary
  {
  public:
    /** What Γc reads, by reference (their current values are used at each call). */
    struct View
    {
      const ContactSpaces<dim>                           &spaces;
      const BodyMesh<dim>                                &body_mesh;
      const std::unique_ptr<Discretization::FEPair<dim>> &fe_pair;
      /** the displacement's DoFs: the faces are its cells' */
      const DoFHandler<dim> &dof_handler_u;
      /** the rule of the contact points on an uncut face */
      const Quadrature<dim - 1>            &contact_quadrature;
      const Parameters::Contact            &parameters;
      const Parameters::AdaptiveRefinement &adaptive_refinement;
      /** the contact zones: each point's zone is set when the points are made */
      Contact::FrictionZones &zones;
      /** r_n, r_t and the conditions chosen (choose_complementarity() writes them) */
      ChosenParameters &chosen;
      /** the law at one point (pairing, threshold, status) */
      const StabilizedPointLaw<dim>                &law;
      const std::unique_ptr<Contact::Partner<dim>> &partner;
      /** relevant: the iterate */
      const TrilinosWrappers::MPI::Vector &ghosted_solution;
      const IndexSet                      &locally_owned;
      const IndexSet                      &locally_relevant;
      /** the displacement DoFs come first; the multipliers after them */
      const types::global_dof_index   &n_u;
      const AffineConstraints<double> &hanging_constraints;
      const LoopPolicy                &loops;
      const double                    &negligible_pressure;
      const MPI_Comm                   communicator;
      const ConditionalOStream        &pcout;
    };

    /** @brief Γc as @p view shows it (empty until setup()). */
    explicit ContactBoundary(const View &view)
        : view(view)
    {
    }

    /**
     * @brief `Complementarity = automatic`: weighted for two deformable bodies
     * and dual pairs, pointwise against a rigid obstacle and where weighted does
     * not apply (doc/formulation.md, "Which conditions by default"), into
     * ChosenParameters::complementarity; once per run, before the first mesh.
     * Contact zones with the weighted conditions, which have no zones, are refused.
     */
    void
    choose_complementarity();

    /**
     * @brief The faces and points of this mesh, unpaired: each face's nodal
     * weights and dual basis, each point's zone and (where it does not depend
     * on the pressure) friction threshold; and the contact conditions on them.
     */
    void
    setup();

    /**
     * @brief Cut the contact faces into segments at the projections of the
     * deformed master's vertices (2D) or into the parts of the projected master
     * faces (3D), keeping the points of the faces whose segments did not change;
     * the changed faces' points are new (unpaired). Collective: returns whether
     * any face changed on any rank.
     */
    bool
    update_segments();

    /** @brief The contact faces of the locally owned cells. */
    const std::vector<ContactFace<dim>> &
    faces() const
    {
      return contact_faces;
    }

    /** @brief The state of the @p q-th contact point of @p face. */
    ContactPointState<dim> &
    point(const ContactFace<dim> &face, const unsigned int q)
    {
      return states[face.first_point + q];
    }
    const ContactPointState<dim> &
    point(const ContactFace<dim> &face, const unsigned int q) const
    {
      return states[face.first_point + q];
    }

    /** @brief The states of all locally owned contact points, face by face; for tests. */
    std::vector<ContactPointState<dim>> &
    points()
    {
      return states;
    }

    /** @brief The contact conditions of this mesh (after setup()). */
    ContactConditions<dim> &
    conditions() const
    {
      Assert(condition_set, ExcMessage("the contact conditions are made by setup()"));
      return *condition_set;
    }

    /** @brief Call f(state, kinematics) at every locally owned contact point, nothing
     * re-evaluated. */
    template <typename Function>
    void
    visit_points(const Function &f)
    {
      FaceEvaluator<dim> evaluator(view.spaces, view.contact_quadrature);
      for (const auto &face : contact_faces)
        {
          evaluator.reinit(face, view.ghosted_solution);
          for (unsigned int q = 0; q < evaluator.n_points(); ++q)
            f(point(face, q), evaluator.kinematics(q));
        }
    }

    /**
     * @brief At every locally owned contact point, evaluate what @p what names
     * (StabilizedPointLaw::evaluate_point_state()) and call f(before, state,
     * kinematics) with the state before and after.
     */
    template <typename Function>
    void
    refresh_points(const PointRefresh &what, const Function &f)
    {
      visit_points([&](ContactPointState<dim> &state, ContactKinematics<dim> k) {
        const ContactPointState<dim> before = state;
        view.law.evaluate_point_state(state, k, what);
        f(before, state, k);
      });
    }

    /** @brief Call f(state, kinematics) at every locally owned contact point, its state
     * frozen. */
    template <typename Function>
    void
    for_each_point(const Function &f)
    {
      visit_points([&](ContactPointState<dim> &state, ContactKinematics<dim> k) {
        view.law.evaluate_point_state(state, k, PointRefresh());
        f(state, k);
      });
    }

    /** @brief Collective: the number of contact points whose status χ is contact. */
    unsigned int
    points_in_contact() const;

    /**
     * @brief The converged state at the points @p nodes of every contact face,
     * evaluated afresh at the iterate, with the conditions' tractions (the
     * nearest node's, with weighted conditions). The partner must be in the
     * iterate's configuration.
     */
    std::vector<ContactSample<dim>>
    sample(const Quadrature<dim - 1> &nodes) const;

    /**
     * @brief The multiplier mass matrix M_jk = ∫_Γc ψ_j φ_k of this rank's
     * contact faces, per pair of multiplier nodes (their λ_n DoFs): ψ_j the
     * run's multiplier basis, φ_k the standard (nodal) one. Diagonal,
     * D_jj = ∫φ_j, with a dual pair. The entries of nodes shared with another
     * rank are this rank's part.
     */
    std::map<std::pair<types::global_dof_index, types::global_dof_index>, double>
    multiplier_mass() const;

    /**
     * @brief With `Complementarity = weighted`, freeze the status of the k-th
     * owned multiplier node to @p in_contact(k) and every threshold to
     * @p threshold; for tests. Returns the number of owned nodes.
     */
    unsigned int
    freeze_nodal_conditions(const std::function<bool(unsigned int)> &in_contact,
                            const double                             threshold)
    {
      return conditions().freeze(in_contact, threshold);
    }

    /**
     * @brief Add Γc's entries to the run's state (@p state_list): the faces'
     * segments (they set the points' layout, so they are read first), the
     * points' states and the conditions' own state.
     */
    void
    register_state(RunState &state_list);

  private:
    /** The consistent nodal weights of the contact faces (ContactFace::nodal_weights). */
    void
    set_consistent_nodal_weights();
    /** ContactFace::dual_basis of every contact face, with a dual pair. */
    void
    set_dual_multiplier_basis();
    /**
     * The contact conditions of this mesh: refuse, or with `automatic` avoid,
     * the weighted conditions on constrained multiplier nodes.
     */
    void
    setup_conditions();
    /** What the contact conditions read and write. */
    ContactConditionsData<dim>
    conditions_data();
    /**
     * The segments of one contact face from its current corners (@p corners:
     * a FaceEvaluator at the face's vertices): 2D, the cuts at the projected
     * master vertices; 3D, the parts of the projected master faces
     * (Contact::face_segments()); null: nothing to cut.
     */
    std::shared_ptr<const Quadrature<dim - 1>>
    face_segments(const FaceEvaluator<dim> &corners) const;
    /** The faces' segment rules, as restore_segments() reads them. */
    std::vector<double>
    segments_list() const;
    /**
     * The contact faces' segment rules of a checkpoint (per face: the number
     * of points, their coordinates, their weights; segments_list()), and the
     * contact points laid out for them: the segments follow the configuration
     * of the checkpoint, not the mesh's initial one.
     */
    void
    restore_segments(const std::vector<double> &segments);
    /** Refuse points read from a checkpoint that do not fit this mesh and scene. */
    void
    check_points(StateReader &in, const std::vector<ContactPointState<dim>> &read) const;

    const View                              view;
    std::vector<ContactFace<dim>>           contact_faces;
    std::vector<ContactPointState<dim>>     states;
    std::unique_ptr<ContactConditions<dim>> condition_set;
    /** With `automatic`: the choice and its reason, logged once the mesh is known */
    std::string complementarity_choice;
  };
} // namespace StabilizedLagrangian
