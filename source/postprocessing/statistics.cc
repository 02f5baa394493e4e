#include <stabilized_lagrangian/postprocessing/statistics.h>

#include <iomanip>

namespace StabilizedLagrangian
{
  void
  StatisticsWriter::open(const std::string &directory, const unsigned int dim, const bool is_root)
  {
    root              = is_root;
    dimension         = dim;
    cumulative_newton = 0;
    cumulative_failed = 0;
    if (!root)
      return;
    statistics_file.close();
    iterations_file.close();
    statistics_file.open(directory + "/statistics.csv");
    iterations_file.open(directory + "/iterations.csv");
    statistics_file
        << "step,time,step_size,step_cuts,geometry_iterations,friction_iterations,"
           "status_iterations,newton_iterations,cumulative_newton_iterations,"
           "failed_attempt_newton_iterations,assemblies,jacobian_assemblies,"
           "final_residual_N,final_scaled_residual,contact_points,points_in_contact,points_stick,"
           "points_slip,normal_force_N,tangential_force_N,contact_force_x_N,"
           "contact_force_y_N";
    if (dim == 3)
      statistics_file << ",contact_force_z_N";
    statistics_file << ",wall_time_s\n";
    iterations_file << "step,geometry_iteration,friction_iteration,status_iteration,"
                       "newton_iterations,residual_N,scaled_residual,status_changes\n";
    statistics_file.flush();
    iterations_file.flush();
  }

  void
  StatisticsWriter::write(const StepStatistics &s)
  {
    cumulative_newton += s.newton_iterations;
    cumulative_failed += s.failed_newton_iterations;
    if (!root)
      return;
    statistics_file << std::setprecision(10) << s.step << ',' << s.time << ',' << s.step_size << ','
                    << s.cuts << ',' << s.geometry_iterations << ',' << s.friction_iterations << ','
                    << s.status_iterations << ',' << s.newton_iterations << ',' << cumulative_newton
                    << ',' << s.failed_newton_iterations << ',' << s.assemblies << ','
                    << s.jacobians << ',' << s.final_residual << ',' << s.final_scaled << ','
                    << s.contact_points << ',' << s.points_in_contact << ',' << s.points_stick
                    << ',' << s.points_slip << ',' << s.normal_force << ',' << s.tangential_force;
    for (unsigned int d = 0; d < dimension; ++d)
      statistics_file << ',' << s.contact_force[d];
    statistics_file << ',' << std::setprecision(4) << s.wall_time << '\n';
    statistics_file.flush();
    for (const auto &r : s.inner_loops)
      iterations_file << s.step << ',' << r.geometry_iteration << ',' << r.friction_iteration << ','
                      << r.status_iteration << ',' << r.newton_iterations << ','
                      << std::setprecision(6) << r.residual << ',' << r.scaled << ','
                      << r.status_changes << '\n';
    iterations_file.flush();
  }
} // namespace StabilizedLagrangian
