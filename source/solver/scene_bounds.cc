#include <stabilized_lagrangian/solver/scene_bounds.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace StabilizedLagrangian
{
  void
  SceneBounds::set_body_diameter(const double diameter)
  {
    body_diameter = diameter;
  }

  void
  SceneBounds::add_prescribed_displacement(const double largest_magnitude)
  {
    if (std::isfinite(largest_magnitude))
      prescribed_displacement = std::max(prescribed_displacement, largest_magnitude);
  }

  void
  SceneBounds::restart()
  {
    prescribed_displacement = 0.;
  }

  double
  SceneBounds::extent() const
  {
    return body_diameter + prescribed_displacement;
  }

  double
  SceneBounds::displacement_scale(const double largest_displacement) const
  {
    // before the mesh is known (extent 0) the iterate is its own scale
    return extent() > 0. ? std::min(largest_displacement, extent()) : largest_displacement;
  }

  std::string
  SceneBounds::implausible(const dealii::TrilinosWrappers::MPI::Vector &vector,
                           const dealii::IndexSet                      &displacement_rows,
                           const std::string                           &what,
                           const MPI_Comm                               communicator) const
  {
    double largest = 0.;
    bool   finite  = true;
    for (const auto i : vector.locally_owned_elements())
      finite = finite && std::isfinite(vector(i));
    for (const auto i : displacement_rows)
      largest = std::max(largest, std::abs(vector(i)));
    finite  = dealii::Utilities::MPI::min(finite ? 1 : 0, communicator) == 1;
    largest = dealii::Utilities::MPI::max(largest, communicator);
    std::ostringstream message;
    if (!finite)
      message << what << " holds values that are not finite";
    else if (extent() > 0. && largest > plausible_factor * extent())
      message << what << " moves a node by " << largest << " mm, " << std::setprecision(2)
              << largest / extent() << " times the scene's extent (the bodies' diameter "
              << body_diameter << " mm plus the largest prescribed displacement "
              << prescribed_displacement << " mm)";
    return message.str();
  }
} // namespace StabilizedLagrangian
