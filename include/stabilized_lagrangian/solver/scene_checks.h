#pragma once

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/distributed/tria_base.h>

#include <deal.II/lac/full_matrix.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/discretization/fe_pair.h>
#include <stabilized_lagrangian/geometry/scene.h>
#include <stabilized_lagrangian/materials/material.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>
#include <stabilized_lagrangian/solver/chosen_parameters.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <vector>

/**
 * @file
 * The checks of a scene before the run (source/solver/scene_checks.cc; those
 * of the rigid obstacle in source/solver/obstacle_checks.cc): the
 * rigid motions its supports leave free, the warnings of a scene that will
 * not solve or not solve well, and the automatic augmentation parameters.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The checks of the scene before the run: whether the supports and
   * the contact hold the body (its free rigid motions), the warnings of a
   * scene that is set up wrong or will answer badly (an obstacle's normal
   * pointing into the body, volumetric locking, a stick traction taking up
   * the pressure checkerboard, a prescribed displacement applied whole in
   * step 1), and the choice of r_n and r_t into ChosenParameters
   * (doc/formulation.md). It reads the scene through a View built anew at
   * each use and owns no state.
   */
  template <int dim> class SceneChecks
  {
  public:
    /** The scene as the checks read it: views of the problem's members, now. */
    struct View
    {
      MPI_Comm                                                                communicator;
      const ConditionalOStream                                               &pcout;
      const parallel::DistributedTriangulationBase<dim>                      &triangulation;
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      /** what the boundary conditions read of the problem (ContactProblem::boundary_view()) */
      const BoundaryConditions::Problem<dim> boundary;
      const Parameters::Contact             &contact_parameters;
      const Parameters::LoadStepping        &load_stepping;
      /** Γc and a second body's master surface, resolved (ChosenParameters) */
      const std::set<types::boundary_id> &contact_boundaries;
      const std::set<types::boundary_id> &master_boundaries;
      /** the Newton system's constraints: hanging nodes and the homogeneous Dirichlet ones */
      const AffineConstraints<double> &newton_constraints;
      /** `Obstacle/Motion`: the rigid obstacle's motion over time */
      const Contact::ObstacleMotion<dim> &obstacle_motion;
      /** the rigid obstacle at rest (`Obstacle`; unused with two bodies) */
      const Obstacles::Interface<dim> &obstacle;
      /** the body's geometry: its boundary names and contact zones */
      const Geometry::Interface<dim> &geometry;
      /** the contact partner; null before the first DoFs are set up */
      const Contact::Partner<dim>                     *partner;
      const Discretization::FEPair<dim>               &fe_pair;
      const std::vector<Materials::BodyMaterial<dim>> &materials;
      /** the material of a cell */
      const std::function<const Materials::Interface<dim> &(
          const typename Triangulation<dim>::cell_iterator &)>
                 material_of;
      const bool axisymmetric;
      const bool any_friction; ///< some zone of Γc has friction
      const bool simplex;      ///< triangles / tetrahedra
    };

    /** @brief Checks of the scene @p view shows. */
    explicit SceneChecks(const View &view);

    /**
     * @brief The warnings before the first step: a body even its contact
     * cannot hold, a body behind the obstacle, an obstacle reaching into the
     * body outside Γc, volumetric locking, a stick-zone traction that
     * oscillates, a Dirichlet condition not ramped, an obstacle motion the
     * scene cannot follow, an obstacle that is no body of revolution in an
     * axisymmetric model.
     */
    void
    warn_before_run() const;

    /**
     * @brief Collective: the rigid motions of the body that no Dirichlet
     * condition holds, in words ("the translation along y"); empty if none
     * (or two bodies). With @p with_contact the contact boundary holds too:
     * along the obstacle's normal at each of its vertices where the contact
     * is frictionless, in every direction where it has friction.
     */
    std::string
    rigid_motions_left_free(bool with_contact = false) const;

    /**
     * @brief Write into @p chosen r_n and r_t: the automatic ones on this
     * mesh (reported), the prm's left as they are.
     */
    void
    choose_augmentation_parameters(ChosenParameters &chosen) const;

  private:
    /** The largest displacement increment the Dirichlet data prescribe over one nominal load step.
     */
    double
    largest_dirichlet_increment() const;
    /** The supports the boundary conditions give (Dirichlet components, stiff springs). */
    std::vector<BoundaryConditions::Support<dim>>
    supports() const;
    /** Collective: whether something holds the axial translation of an axisymmetric body. */
    bool
    axial_translation_held(bool with_contact) const;
    /**
     * Collective: G = Σ m mᵀ over the (vertex, direction) pairs the supports
     * (and with @p with_contact the contact) hold, m the rigid motions
     * there: dim translations, then the rotations about the body's centre,
     * scaled by its size.
     */
    FullMatrix<double>
    rigid_motion_gram(bool with_contact) const;
    /** The eigenvectors of @p gram with a zero eigenvalue (columns of the result), in words. */
    static std::string
    describe_free_motions(const FullMatrix<double> &gram);
    /** Call f(vertex) at every vertex of the faces of boundary @p boundary_id on this rank's cells.
     */
    template <typename Function>
    void
    for_each_boundary_vertex(const types::boundary_id boundary_id, const Function &f) const
    {
      BoundaryConditions::for_each_boundary_vertex<dim>(view.triangulation, boundary_id, f);
    }
    /**
     * Warn of a body that even its contact cannot hold (a frictionless contact
     * holds only the normal direction): its Newton system is singular.
     */
    void
    check_body_is_held() const;
    /**
     * Warn of an `Obstacle/Motion` the scene cannot follow: with two
     * deformable bodies there is no obstacle to move; in an axisymmetric
     * model only a motion along the axis keeps the obstacle a body of
     * revolution about it.
     */
    void
    warn_if_obstacle_motion_ignored() const;
    /**
     * Warn when a prescribed displacement is not zero at t = 0 (applied whole
     * in step 1), or a support takes a load (a point load on a held vertex).
     */
    void
    warn_of_boundary_conditions() const;
    /** Warn when a material is nearly incompressible for the displacement degree (locking). */
    void
    warn_if_pair_locks() const;
    /**
     * Warn when F-bar or mixed on Q1 (the Q1/P0 mean dilatation) meets friction
     * multipliers at every contact node near incompressibility: the stick-zone
     * traction takes up the pressure checkerboard mode.
     */
    void
    warn_if_stick_traction_oscillates() const;
    /** Warn when most of the body starts behind the rigid obstacle's surface; true if it warned. */
    bool
    warn_if_body_behind_obstacle() const;
    /**
     * Warn when the rigid obstacle reaches into the body's boundary outside
     * Γc (`Contact/Contact boundary ids`), where nothing keeps it out: at
     * the body's boundary vertices off Γc, before the first step, and at the
     * end time with the obstacle where `Obstacle/Motion` takes it and the
     * body undeformed (its deformation is not known before the run), there
     * only on faces that face the obstacle and deeper than half its reach
     * into Γc, which the contact pushes back.
     */
    void
    warn_if_body_passes_through_obstacle() const;
    /** The vertices of Γc on this rank's cells and ghosts (their indices in the triangulation). */
    std::set<unsigned int>
    contact_vertices() const;
    /**
     * The warning of warn_if_body_passes_through_obstacle(): the obstacle
     * reaches into @p boundaries, each as @p reached says (a line each).
     */
    void
    report_pass_through(const std::set<types::boundary_id> &boundaries,
                        const std::string                  &reached) const;
    /** "boundary 'name' (id 1)", or "boundary 1" when the geometry names no boundary @p id. */
    std::string
    boundary_label(types::boundary_id id) const;
    /**
     * Warn when the model is axisymmetric and the obstacle is no body of
     * revolution about its axis (Obstacles::Interface::axisymmetry_defect()).
     */
    void
    warn_if_obstacle_not_of_revolution() const;

    const View view;
  };
} // namespace StabilizedLagrangian
