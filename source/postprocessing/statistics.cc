#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <iomanip>
#include <sstream>

namespace StabilizedLagrangian
{
  namespace
  {
    /** What one row of statistics.csv is written from. */
    struct StepRow
    {
      const StepStatistics &record;
      unsigned int          cumulative_newton; ///< with this step's
    };

    /** What one row of iterations.csv is written from. */
    struct LoopRow
    {
      const InnerLoopRecord &record;
      unsigned int           step;
    };

    /** One column of a CSV file: its header and how a row writes its value. */
    template <typename Row> struct Column
    {
      std::string                                      name;
      std::function<void(std::ostream &, const Row &)> write;
    };

    /** The column @p name showing @p member of the row's record with @p precision digits. */
    template <typename Row, typename Member>
    Column<Row>
    member_column(const std::string &name, const Member member, const int precision)
    {
      return {name, [member, precision](std::ostream &out, const Row &row) {
                out << std::setprecision(precision) << row.record.*member;
              }};
    }

    /** The columns of statistics.csv, in their order (a new statistic is one entry). */
    std::vector<Column<StepRow>>
    statistics_columns(const unsigned int dim, const StatisticsWriter::Supports &supports)
    {
      const auto        &reactions = supports.reaction_boundaries;
      const std::string &N         = supports.force_unit;
      const auto field = [](const std::string &name, const auto member, const int precision = 10) {
        return member_column<StepRow>(name, member, precision);
      };
      using S                              = StepStatistics;
      std::vector<Column<StepRow>> columns = {
          field("step", &S::step),
          field("time", &S::time),
          field("step_size", &S::step_size),
          field("step_cuts", &S::cuts),
          field("geometry_iterations", &S::geometry_iterations),
          field("friction_iterations", &S::friction_iterations),
          field("status_iterations", &S::status_iterations),
          field("newton_iterations", &S::newton_iterations),
          {"cumulative_newton_iterations",
           [](std::ostream &out, const StepRow &row) { out << row.cumulative_newton; }},
          field("failed_attempt_newton_iterations", &S::failed_newton_iterations),
          field("assemblies", &S::assemblies),
          field("jacobian_assemblies", &S::jacobians),
          field("final_residual_" + N, &S::final_residual),
          field("final_scaled_residual", &S::final_scaled),
          field("contact_points", &S::contact_points),
          field("points_in_contact", &S::points_in_contact),
          field("points_stick", &S::points_stick),
          field("points_slip", &S::points_slip),
          field("normal_force_" + N, &S::normal_force),
          field("tangential_force_" + N, &S::tangential_force)};
      for (unsigned int d = 0; d < dim; ++d)
        columns.push_back({std::string("contact_force_") + "xyz"[d] + "_" + N,
                           [d](std::ostream &out, const StepRow &row) {
                             out << std::setprecision(10) << row.record.contact_force[d];
                           }});
      for (unsigned int b = 0; b < reactions.size(); ++b)
        for (unsigned int d = 0; d < dim; ++d)
          columns.push_back(
              {"reaction_boundary_" + std::to_string(reactions[b]) + "_" + "xyz"[d] + "_" + N,
               [b, d](std::ostream &out, const StepRow &row) {
                 out << std::setprecision(10) << row.record.reactions[b][d];
               }});
      for (unsigned int p = 0; p < supports.reaction_points.size(); ++p)
        for (unsigned int d = 0; d < dim; ++d)
          columns.push_back(
              {"reaction_point_" + supports.reaction_points[p] + "_" + "xyz"[d] + "_" + N,
               [p, d](std::ostream &out, const StepRow &row) {
                 out << std::setprecision(10) << row.record.point_reactions[p][d];
               }});
      const auto &own = supports.condition_columns;
      for (unsigned int group = 0, n_groups = 1; group < n_groups; ++group)
        for (unsigned int k = 0; k < own.size(); ++k)
          {
            n_groups = std::max(n_groups, own[k].group + 1);
            if (own[k].group == group)
              columns.push_back({own[k].name, [k](std::ostream &out, const StepRow &row) {
                                   out << std::setprecision(10) << row.record.condition_values[k];
                                 }});
          }
      for (unsigned int z = 0; z < supports.zones.size(); ++z)
        for (const unsigned int k : {0u, 1u})
          columns.push_back(
              {"zone_" + supports.zones[z] + (k == 0 ? "_normal_force_" : "_tangential_force_") + N,
               [z, k](std::ostream &out, const StepRow &row) {
                 out << std::setprecision(10) << row.record.zone_forces[z][k];
               }});
      columns.push_back(field("folded_loops", &S::folded_loops));
      columns.push_back(field("adaptive_stops", &S::adaptive_stops));
      columns.push_back(field("friction_law_violations", &S::friction_law_violations));
      columns.push_back(field("estimated_error_sqrtNmm", &S::estimated_error, 6));
      columns.push_back(field("estimated_contact_error_sqrtNmm", &S::estimated_contact_error, 6));
      columns.push_back(field("energy_norm_sqrtNmm", &S::energy_norm, 10));
      columns.push_back(field("estimated_pressure_error", &S::estimated_pressure_error, 6));
      columns.push_back({"estimated_relative_error", [](std::ostream &out, const StepRow &row) {
                           out << std::setprecision(6) << row.record.relative_error();
                         }});
      columns.push_back(field("wall_time_s", &S::wall_time, 4));
      return columns;
    }

    /** The columns of iterations.csv, in their order. */
    std::vector<Column<LoopRow>>
    iterations_columns(const std::string &N)
    {
      const auto field = [](const std::string &name, const auto member) {
        return member_column<LoopRow>(name, member, 6);
      };
      using R = InnerLoopRecord;
      return {{"step", [](std::ostream &out, const LoopRow &row) { out << row.step; }},
              field("geometry_iteration", &R::geometry_iteration),
              field("friction_iteration", &R::friction_iteration),
              field("status_iteration", &R::status_iteration),
              field("newton_iterations", &R::newton_iterations),
              field("residual_" + N, &R::residual),
              field("scaled_residual", &R::scaled),
              field("status_changes", &R::status_changes)};
    }

    /** The header line of @p columns. */
    template <typename Row>
    std::string
    header(const std::vector<Column<Row>> &columns)
    {
      std::string line;
      for (const auto &column : columns)
        line += (line.empty() ? "" : ",") + column.name;
      return line + '\n';
    }

    /** Append the line of @p row to @p out. */
    template <typename Row>
    void
    write_line(std::ostream &out, const std::vector<Column<Row>> &columns, const Row &row)
    {
      for (unsigned int c = 0; c < columns.size(); ++c)
        {
          if (c > 0)
            out << ',';
          columns[c].write(out, row);
        }
      out << '\n';
    }
  } // namespace

  void
  StatisticsWriter::open(const std::string &directory,
                         const unsigned int dim,
                         const bool         is_root,
                         const Supports    &columns_of)
  {
    resume(directory, dim, is_root, columns_of, State());
    if (!root)
      return;
    SafeFiles::write_atomically(statistics_path, header(statistics_columns(dim, supports)));
    SafeFiles::write_atomically(iterations_path, header(iterations_columns(supports.force_unit)));
  }

  void
  StatisticsWriter::resume(const std::string &directory,
                           const unsigned int dim,
                           const bool         is_root,
                           const Supports    &columns_of,
                           const State       &state)
  {
    root              = is_root;
    dimension         = dim;
    supports          = columns_of;
    cumulative_newton = state.cumulative_newton;
    cumulative_failed = state.cumulative_failed;
    statistics_path   = directory + "/statistics.csv";
    iterations_path   = directory + "/iterations.csv";
    if (root && state.statistics_bytes > 0)
      {
        SafeFiles::truncate(statistics_path, state.statistics_bytes);
        SafeFiles::truncate(iterations_path, state.iterations_bytes);
      }
  }

  StatisticsWriter::State
  StatisticsWriter::state() const
  {
    State state;
    state.cumulative_newton = cumulative_newton;
    state.cumulative_failed = cumulative_failed;
    if (root)
      {
        state.statistics_bytes = std::filesystem::file_size(statistics_path);
        state.iterations_bytes = std::filesystem::file_size(iterations_path);
      }
    return state;
  }

  void
  StatisticsWriter::write(const StepStatistics &s)
  {
    cumulative_newton += s.newton_iterations;
    cumulative_failed += s.failed_newton_iterations;
    if (!root)
      return;
    std::ostringstream row;
    write_line(row, statistics_columns(dimension, supports), StepRow{s, cumulative_newton});
    std::ostringstream                 rows;
    const std::vector<Column<LoopRow>> columns = iterations_columns(supports.force_unit);
    for (const auto &r : s.inner_loops)
      write_line(rows, columns, LoopRow{r, s.step});
    // the iterations first: a statistics row always has its inner loops
    SafeFiles::append(iterations_path, rows.str());
    SafeFiles::append(statistics_path, row.str());
  }
} // namespace StabilizedLagrangian
