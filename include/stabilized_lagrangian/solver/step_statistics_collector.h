#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/base/quadrature.h>

#include <deal.II/lac/trilinos_vector.h>

#include <stabilized_lagrangian/boundary_conditions/interface.h>
#include <stabilized_lagrangian/contact/contact_conditions.h>
#include <stabilized_lagrangian/contact/friction_zones.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>

#include <functional>
#include <memory>
#include <utility>
#include <vector>

/**
 * @file
 * What statistics.csv records of a converged load step besides the loops'
 * counts: the contact counts and forces, the check of the friction law at the
 * multiplier rows, the reactions of the supported boundaries and the
 * conditions' own columns.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief The statistics of a converged load step and the columns of
   * statistics.csv they fill. It owns nothing: it reads the converged state
   * through a View and writes the points in contact (the active set the
   * adaptive refinement follows) through it.
   */
  template <int dim> class StepStatisticsCollector
  {
  public:
    /** What the statistics read of the problem, and (named so) what they write. */
    struct View
    {
      /** the converged iterate (owned) and its residual, without the Dirichlet rows */
      const TrilinosWrappers::MPI::Vector &solution;
      const TrilinosWrappers::MPI::Vector &residual;
      const IndexSet                      &locally_owned_u;
      /** the multiplier element component (0: λ_n, 1..: Λ) of each owned multiplier row */
      const std::vector<std::pair<types::global_dof_index, unsigned int>> &multiplier_components;
      /** per owned multiplier row, the weight that turns its residual into a length */
      const TrilinosWrappers::MPI::Vector &multiplier_length_weights;
      /** the contact conditions: their counts and forces */
      ContactConditions<dim> &conditions;
      /** `Nonlinear solver/Friction tolerance` */
      const double friction_tolerance;
      /** the nodal forces of the last assembly: internal, external and the contact terms */
      const TrilinosWrappers::MPI::Vector &internal_force;
      const TrilinosWrappers::MPI::Vector &external_force;
      const TrilinosWrappers::MPI::Vector &contact_residual;
      /** the boundary condition plug-ins and what they read of the problem */
      const std::vector<std::unique_ptr<BoundaryConditions::Interface<dim>>> &boundary_conditions;
      const BoundaryConditions::Problem<dim>                                  boundary;
      /** the face quadrature of the displacement's space (the springs' force) */
      const Quadrature<dim - 1>     face_quadrature;
      const Contact::FrictionZones &zones;
      /** N, or per unit thickness in plane strain N_per_mm (a column name's suffix) */
      const std::string force_unit;
      const MPI_Comm    communicator;
      /** the displacement of the converged state, ghosted */
      std::function<TrilinosWrappers::MPI::Vector()> ghosted_displacement;
      /** written: the reference positions of this rank's points in contact */
      std::vector<Point<dim>> &active_set;
    };

    /** @brief The statistics of the converged state @p view shows. */
    explicit StepStatisticsCollector(const View &view)
        : view(view)
    {
    }

    /**
     * @brief Forces and point counts of the converged step into @p stats, the
     * friction law's check at the multiplier rows and the reactions; records
     * the active set.
     */
    void
    collect(StepStatistics &stats) const;

    /**
     * @brief The supports statistics.csv has columns for: the supported
     * boundaries, the conditions' own, the contact zones.
     */
    StatisticsWriter::Supports
    supports() const;

  private:
    /**
     * The boundary ids with a Dirichlet condition or springs, each once: the
     * Dirichlet ones in the order of their subsections, then the springs'.
     */
    std::vector<types::boundary_id>
    supported_boundaries() const;
    /**
     * The reaction of each supported boundary of the converged state, into
     * stats.reactions: the sum over its constrained DoFs of the residual
     * without constraints (internal minus applied forces plus the contact
     * terms; a DoF on two such boundaries counts for the first), plus the
     * springs' force ∫ −K (u − u_0); and the conditions' own statistics.
     */
    void
    add_reactions(StepStatistics &stats) const;

    const View view;
  };
} // namespace StabilizedLagrangian
