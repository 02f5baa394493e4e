#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <stabilized_lagrangian/contact/cumulative_slip.h>
#include <stabilized_lagrangian/contact/partner.h>
#include <stabilized_lagrangian/obstacles/obstacle.h>
#include <stabilized_lagrangian/parameters.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

/**
 * @file
 * The output of a converged state: the VTU of the body and of the contact
 * surface, the profile of Γc, the rigid obstacle, and the .pvd records that
 * list them. The writer reads what it writes through a view; it computes
 * nothing a later step needs.
 */

namespace StabilizedLagrangian
{
  using namespace dealii;

  /**
   * @brief One output field of Γc: a Q1 (P1) field of the VTU, averaged at
   * the vertices of Γc, and columns of the profile, at every node of Γc; both
   * evaluated from a sample of the converged state (doc/formulation.md).
   */
  template <int dim> struct ContactOutputField
  {
    std::string  name;       ///< of the VTU field
    std::string  column;     ///< the profile's columns are column[_x|_y|_z][_unit]
    std::string  unit;       ///< empty for a number without unit
    unsigned int components; ///< 1 (a scalar) or dim (a vector)
    /** append the field's components at a sample to the values */
    std::function<void(const ContactSample<dim> &, std::vector<double> &)> evaluate;
  };

  /**
   * @brief The cell averages of the Cauchy stress and of the materials'
   * history fields over the active cells (zero on the cells of other ranks).
   */
  struct CellAverages
  {
    std::vector<Tensor<2, 3>>  stress;
    std::vector<std::string>   history_names; ///< every material's, each name once
    std::vector<Vector<float>> history_fields;
  };

  /**
   * @brief The writer of a run's output files: solution_<step>.pvtu,
   * contact_surface_<step>.pvtu, profile-<step>.csv, obstacle_<step>.vtu and
   * the .pvd files that list the steps written. It owns the table of the
   * contact output fields and the .pvd records (part of the run's state).
   */
  template <int dim> class SolutionOutput
  {
  public:
    /** The converged state an output shows, read-only: views of the problem's members. */
    struct View
    {
      const Triangulation<dim>            &triangulation;
      const DoFHandler<dim>               &displacement_dofs;
      const TrilinosWrappers::MPI::Vector &displacement; ///< ghosted
      unsigned int                         displacement_degree;
      bool                                 simplex;      ///< triangles / tetrahedra
      bool                                 axisymmetric; ///< the hoop stress is a field
      /** empty unless writes_vtu() */
      const CellAverages &cell_averages;
      /** η_K of the residual error estimate (√(N mm)), per active cell */
      const Vector<float> &error_indicators;
      /** whether face f of a cell lies on Γc */
      const std::function<bool(const typename Triangulation<dim>::cell_iterator &, unsigned int)>
                                            &is_contact_face;
      unsigned int                           n_contact_faces; ///< this rank's
      const std::vector<ContactSample<dim>> &contact_samples;
      /** the rigid obstacle, null for a deformable partner */
      const Obstacles::Interface<dim>    *rigid_obstacle;
      const Contact::ObstacleMotion<dim> &obstacle_motion;
    };

    /**
     * @brief A writer on @p communicator of the files @p parameters ask for
     * (`Write vtu`, `Write profiles`).
     */
    SolutionOutput(MPI_Comm communicator, const Parameters::Output &parameters);

    /** @brief Whether the VTU is written (and needs the cell averages). */
    bool
    writes_vtu() const
    {
      return write_vtu;
    }

    /**
     * @brief Create @p directory and remove what an earlier run wrote there
     * (the files this program writes: solution, profiles, statistics, cycles,
     * checkpoints), after the input was read; an InputError names the entry.
     */
    void
    prepare_directory(const std::string &directory) const;

    /**
     * @brief Write the output of @p step at time @p t into @p directory: the
     * VTU of the body and of Γc, listed in the .pvd files, the rigid
     * obstacle, and (after step 0) the profile. Collective.
     */
    void
    write(unsigned int step, double t, const View &view, const std::string &directory);

    /** @brief Write solution.pvd and contact_surface.pvd from the records (rank 0). */
    void
    write_pvd(const std::string &directory) const;

    /** @brief The VTU files written so far, with their times (solution_<step>.pvtu). */
    const std::vector<std::pair<double, std::string>> &
    records() const
    {
      return pvd_records;
    }

    /** @brief Continue from @p records (a checkpoint's; none for a new load path). */
    void
    set_records(const std::vector<std::pair<double, std::string>> &records)
    {
      pvd_records = records;
    }

  private:
    /**
     * The contact fields at the samples: averaged at the vertices into
     * @p vertex_values (a Q1 field of @p field_dofs), each node's reference
     * coordinates and values appended to @p profile.
     */
    void
    sample_contact_fields(const View                    &view,
                          const DoFHandler<dim>         &field_dofs,
                          TrilinosWrappers::MPI::Vector &vertex_values,
                          std::vector<double>           &profile) const;
    /** The VTU of @p step with the contact fields, listed in solution.pvd. */
    void
    write_solution(unsigned int                         step,
                   double                               t,
                   const View                          &view,
                   const std::string                   &directory,
                   const DoFHandler<dim>               &field_dofs,
                   const TrilinosWrappers::MPI::Vector &vertex_values);
    /**
     * The VTU of Γc itself, contact_surface_<step>.pvtu: the contact fields
     * at its vertices, not smeared into cells (a piece per rank that holds
     * contact faces).
     */
    void
    write_contact_surface(unsigned int                         step,
                          const View                          &view,
                          const std::string                   &directory,
                          const DoFHandler<dim>               &field_dofs,
                          const TrilinosWrappers::MPI::Vector &vertex_values) const;
    /** profile-<step>.csv: one row per node of Γc (rank 0, from every rank's @p profile). */
    void
    write_profile(unsigned int               step,
                  const std::string         &directory,
                  const std::vector<double> &profile) const;
    /**
     * The rigid obstacle's surface at time @p t, moved by its motion, as
     * obstacle_<step>.vtu, and obstacle.pvd beside solution.pvd (rank 0;
     * nothing for a deformable master).
     */
    void
    write_obstacle(unsigned int       step,
                   double             t,
                   const View        &view,
                   const std::string &directory) const;

    MPI_Comm   communicator;
    const bool write_vtu;
    const bool write_profiles;
    /** the contact output fields, in the order of the VTU's and the profile's */
    const std::vector<ContactOutputField<dim>>  contact_fields;
    std::vector<std::pair<double, std::string>> pvd_records;
  };
} // namespace StabilizedLagrangian
