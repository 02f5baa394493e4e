#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/trilinos_vector.h>

#include <string>

namespace StabilizedLagrangian
{
  /**
   * @brief The sizes the scene implies, against which an iterate is judged
   * (doc/formulation.md, "What a converged state must satisfy").
   *
   * The scaled Newton criterion measures the residual's blocks against the
   * iterate's own displacements; a diverged iterate (a singular system's
   * solution, a body flung 10^11 mm away by a load nothing resists) then
   * judges itself converged. These bounds come from the problem instead: the
   * size of the meshed bodies and the largest prescribed displacement so far.
   * No quasi-static contact state moves a node a hundred times further than
   * both; an update or a converged state that does is refused, with the
   * cause named.
   */
  class SceneBounds
  {
  public:
    /**
     * A displacement at most this multiple of the scene's extent (the bodies'
     * diameter plus the largest prescribed displacement) is plausible.
     */
    static constexpr double plausible_factor = 100.;

    /** @brief The diameter of the meshed bodies (mm), from the mesh. */
    void
    set_body_diameter(double diameter);

    /**
     * @brief Take the prescribed displacements of a load step: the largest
     * magnitude (mm) among them, over all ranks, widens the scene's extent.
     */
    void
    add_prescribed_displacement(double largest_magnitude);

    /** @brief Forget the prescribed displacements (a new load path). */
    void
    restart();

    /** @brief The bodies' diameter plus the largest prescribed displacement (mm). */
    double
    extent() const;

    /**
     * @brief The displacement against which the scaled criterion measures its
     * blocks: the iterate's largest displacement, but never more than the
     * scene's extent (a diverged iterate may not enlarge its own yardstick).
     */
    double
    displacement_scale(double largest_displacement) const;

    /**
     * @brief Why @p vector (a Newton update, or the solution) is implausible,
     * or an empty string: a value that is not finite, or a displacement beyond
     * plausible_factor times the extent.
     * @param vector the vector to check
     * @param displacement_rows the locally owned displacement rows
     * @param what what the vector is, for the message ("the Newton update")
     * @param communicator the result is the same on every rank
     */
    std::string
    implausible(const dealii::TrilinosWrappers::MPI::Vector &vector,
                const dealii::IndexSet                      &displacement_rows,
                const std::string                           &what,
                const MPI_Comm                               communicator) const;

  private:
    double body_diameter           = 0.;
    double prescribed_displacement = 0.;
  };
} // namespace StabilizedLagrangian
