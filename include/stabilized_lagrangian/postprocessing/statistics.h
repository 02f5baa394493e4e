#pragma once

#include <deal.II/base/types.h>

#include <array>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace StabilizedLagrangian
{
  /**
   * @brief One innermost loop of the nested algorithm: the Newton iterations
   * of one status iteration (one row of iterations.csv, the seed's table).
   */
  struct InnerLoopRecord
  {
    unsigned int geometry_iteration;
    unsigned int friction_iteration;
    unsigned int status_iteration;
    unsigned int newton_iterations;
    double       residual; ///< in N (multiplier rows scaled by r_n, r_t)
    double       scaled;   ///< the largest block against its scale (ScaledResidual)
    unsigned int status_changes;
  };

  /**
   * @brief Statistics of one load step (one row of statistics.csv; doc/formulation.md,
   * "Nested loops"). A statistic is a member here and its column in the table
   * of statistics.cc, which writes both the header and the rows.
   */
  /**
   * The unit of forces of a model: N in 3D and axisymmetric, else per unit
   * thickness (plane strain) N/mm; @p column: as a column name's suffix, N_per_mm.
   */
  inline std::string
  force_unit(const int dim, const bool axisymmetric, const bool column)
  {
    if (dim == 3 || axisymmetric)
      return "N";
    return column ? "N_per_mm" : "N/mm";
  }

  struct StepStatistics
  {
    unsigned int step                = 0;
    double       time                = 0.;
    double       step_size           = 0.;
    unsigned int cuts                = 0;
    unsigned int geometry_iterations = 0;
    unsigned int friction_iterations = 0;
    unsigned int status_iterations   = 0;
    unsigned int newton_iterations   = 0;
    double       final_residual      = 0.; ///< in N
    double       final_scaled        = 0.; ///< largest scaled block
    /** Newton iterations of the attempts that failed and were cut (not in newton_iterations) */
    unsigned int          failed_newton_iterations = 0;
    unsigned int          assemblies               = 0; ///< all attempts
    unsigned int          jacobians                = 0; ///< all attempts
    unsigned int          contact_points           = 0;
    unsigned int          points_in_contact        = 0;
    unsigned int          points_stick             = 0;
    unsigned int          points_slip              = 0;
    double                normal_force             = 0.;
    double                tangential_force         = 0.;
    std::array<double, 3> contact_force            = {{0., 0., 0.}};
    /**
     * The force each Dirichlet boundary exerts on the body (N; N/mm in 2D), in
     * the order of StatisticsWriter's reaction boundaries
     */
    std::vector<std::array<double, 3>> reactions;
    /** the force each point Dirichlet condition exerts on the body (N; N/mm in 2D) */
    std::vector<std::array<double, 3>> point_reactions;
    /**
     * the boundary conditions' own columns' values, in the order
     * StatisticsWriter::Supports::condition_columns lists them
     */
    std::vector<double> condition_values;
    /** each contact zone's normal and tangential force (N; N/mm in 2D), as the totals' */
    std::vector<std::array<double, 2>> zone_forces;
    /** fixed-point loops that cycled or did not converge and were folded into Newton */
    unsigned int folded_loops = 0;
    /**
     * `Stopping = adaptive`: the loops (Newton's and the nest's) that stopped
     * because their error fell below the fraction of the estimate, before
     * their own criterion
     */
    unsigned int adaptive_stops = 0;
    /** points in contact that break the law they report (Contact::FrictionLawCheck) */
    unsigned int friction_law_violations = 0;
    std::string  friction_law_report; ///< what broke it, where; empty if nothing
    /** the residual error estimate η in the energy norm (√(N mm); doc/formulation.md) */
    double estimated_error = 0.;
    /** its contact part η_C (√(N mm)) */
    double estimated_contact_error = 0.;
    /**
     * the relative L2 mismatch on Γc between the normal traction of the
     * stress and the contact pressure, ‖P N·n − λ_n‖ / ‖λ_n‖: an estimate of
     * the relative L2 error of the pressure (doc/formulation.md)
     */
    double estimated_pressure_error = 0.;
    /** the energy norm of the solution, (∫ P:∇u)^½ (√(N mm)) */
    double energy_norm = 0.;
    /** @brief η against the energy norm of the solution (0 for an undeformed body). */
    double
    relative_error() const
    {
      return energy_norm > 0. ? estimated_error / energy_norm : 0.;
    }
    double                       wall_time = 0.;
    std::vector<InnerLoopRecord> inner_loops;
  };

  /**
   * @brief A CSV file of one row as a table (run_summary.csv): one column per
   * add(), its name and its value as a stream writes it, so that a column is
   * added in one place.
   */
  class SummaryRow
  {
  public:
    /** @brief Add the column @p name showing @p value. */
    template <typename Value>
    void
    add(const std::string &name, const Value &value)
    {
      std::ostringstream text;
      text << value;
      columns.emplace_back(name, text.str());
    }

    /** @brief The header line and the row. */
    std::string
    csv() const
    {
      std::string header, row;
      for (std::size_t c = 0; c < columns.size(); ++c)
        {
          header += (c > 0 ? "," : "") + columns[c].first;
          row += (c > 0 ? "," : "") + columns[c].second;
        }
      return header + '\n' + row + '\n';
    }

  private:
    std::vector<std::pair<std::string, std::string>> columns;
  };

  /**
   * @brief Writes statistics.csv and iterations.csv on rank 0, the rows of one
   * load step appended in one write (SafeFiles::append), so a run killed at any
   * moment leaves whole rows, and the rows of converged steps survive a failing run.
   */
  class StatisticsWriter
  {
  public:
    /** @brief The supports whose columns the rows show. */
    struct Supports
    {
      /** the Dirichlet and spring boundaries: reaction_boundary_<id>_<axis>_N */
      std::vector<dealii::types::boundary_id> reaction_boundaries;
      /** the point Dirichlet conditions' names: reaction_point_<name>_<axis>_N */
      std::vector<std::string> reaction_points;
      /**
       * @brief A column of a boundary condition's own: its name, and its group:
       * the columns of a group follow those of the groups before it, each group
       * in the order the columns were added.
       */
      struct ConditionColumn
      {
        std::string  name;
        unsigned int group = 0;
      };
      /**
       * the boundary conditions' own columns (BoundaryConditions::Interface::
       * add_statistics_columns(), with force_unit in their names), after the
       * point reactions; StepStatistics::condition_values are in this order
       */
      std::vector<ConditionColumn> condition_columns;
      /** the contact zones' names: zone_<name>_{normal,tangential}_force_N */
      std::vector<std::string> zones;
      /**
       * the unit of the force columns' names: N, or N_per_mm for the forces per
       * unit thickness of a plane strain model (every `_N` above is then
       * `_N_per_mm`)
       */
      std::string force_unit = "N";
    };

    /** @brief What a checkpoint keeps to continue the files where it was taken. */
    struct State
    {
      unsigned long statistics_bytes  = 0; ///< size of statistics.csv
      unsigned long iterations_bytes  = 0; ///< size of iterations.csv
      unsigned int  cumulative_newton = 0;
      unsigned int  cumulative_failed = 0;
    };

    /**
     * @brief Create both files in @p directory and write their headers (rank 0
     * only); restarts the Newton counts.
     */
    void
    open(const std::string &directory,
         const unsigned int dim,
         const bool         is_root,
         const Supports    &supports);

    /**
     * @brief Continue the files of @p directory from a checkpoint: cut them to the
     * rows it knew of (a killed run may have written more) and restore the counts.
     */
    void
    resume(const std::string &directory,
           const unsigned int dim,
           const bool         is_root,
           const Supports    &supports,
           const State       &state);

    /** @brief The state to store in a checkpoint. */
    State
    state() const;

    /** @brief Append the rows of one converged load step. */
    void
    write(const StepStatistics &stats);

    /** @brief Total Newton iterations of the accepted attempts so far. */
    unsigned int
    cumulative_newton_iterations() const
    {
      return cumulative_newton;
    }

    /** @brief Total Newton iterations of the failed (cut) attempts so far. */
    unsigned int
    cumulative_failed_newton_iterations() const
    {
      return cumulative_failed;
    }

  private:
    bool         root      = false;
    unsigned int dimension = 2;
    /** the supports whose columns the rows show */
    Supports     supports;
    unsigned int cumulative_newton = 0;
    unsigned int cumulative_failed = 0;
    std::string  statistics_path;
    std::string  iterations_path;
  };
} // namespace StabilizedLagrangian
