#include <stabilized_lagrangian/postprocessing/safe_files.h>
#include <stabilized_lagrangian/postprocessing/statistics.h>

#include <filesystem>
#include <iomanip>
#include <sstream>

namespace StabilizedLagrangian
{
  void
  StatisticsWriter::open(const std::string &directory, const unsigned int dim, const bool is_root)
  {
    resume(directory, dim, is_root, State());
    if (!root)
      return;
    std::ostringstream header;
    header << "step,time,step_size,step_cuts,geometry_iterations,friction_iterations,"
              "status_iterations,newton_iterations,cumulative_newton_iterations,"
              "failed_attempt_newton_iterations,assemblies,jacobian_assemblies,"
              "final_residual_N,final_scaled_residual,contact_points,points_in_contact,"
              "points_stick,points_slip,normal_force_N,tangential_force_N,contact_force_x_N,"
              "contact_force_y_N";
    if (dim == 3)
      header << ",contact_force_z_N";
    header << ",folded_loops,friction_law_violations,wall_time_s\n";
    SafeFiles::write_atomically(statistics_path, header.str());
    SafeFiles::write_atomically(iterations_path,
                                "step,geometry_iteration,friction_iteration,status_iteration,"
                                "newton_iterations,residual_N,scaled_residual,status_changes\n");
  }

  void
  StatisticsWriter::resume(const std::string &directory,
                           const unsigned int dim,
                           const bool         is_root,
                           const State       &state)
  {
    root              = is_root;
    dimension         = dim;
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
    row << std::setprecision(10) << s.step << ',' << s.time << ',' << s.step_size << ',' << s.cuts
        << ',' << s.geometry_iterations << ',' << s.friction_iterations << ','
        << s.status_iterations << ',' << s.newton_iterations << ',' << cumulative_newton << ','
        << s.failed_newton_iterations << ',' << s.assemblies << ',' << s.jacobians << ','
        << s.final_residual << ',' << s.final_scaled << ',' << s.contact_points << ','
        << s.points_in_contact << ',' << s.points_stick << ',' << s.points_slip << ','
        << s.normal_force << ',' << s.tangential_force;
    for (unsigned int d = 0; d < dimension; ++d)
      row << ',' << s.contact_force[d];
    row << ',' << s.folded_loops << ',' << s.friction_law_violations << ',' << std::setprecision(4)
        << s.wall_time << '\n';
    std::ostringstream rows;
    for (const auto &r : s.inner_loops)
      rows << s.step << ',' << r.geometry_iteration << ',' << r.friction_iteration << ','
           << r.status_iteration << ',' << r.newton_iterations << ',' << std::setprecision(6)
           << r.residual << ',' << r.scaled << ',' << r.status_changes << '\n';
    // the iterations first: a statistics row always has its inner loops
    SafeFiles::append(iterations_path, rows.str());
    SafeFiles::append(statistics_path, row.str());
  }
} // namespace StabilizedLagrangian
