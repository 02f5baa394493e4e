#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief Checks that a converged load step satisfies the contact and friction
     * law it reports (seed eqs. (5)–(8)), apart from the Newton criterion that
     * accepted it.
     *
     * - The multiplier equations, each as a length (the residual of the row over
     *   its weight, as in the scaled residual): the weighted gap where the point
     *   is in contact and the weighted slip where it sticks (in a slipping
     *   region, the mismatch between Λ and the slip direction, times r_t/s).
     *   With the nodal contact quadrature these are the points' own gap and slip;
     *   with a multiplier space coarser than the trace (Q2/P1) the law holds in
     *   this weak sense only, and that is what is checked. Allowed: the fraction
     *   `length_tolerance` of the largest displacement.
     * - The tangential traction at each contact point within the threshold,
     *   |t_t| ≤ s(λ_n), up to the friction loop's tolerance of the largest
     *   threshold.
     *
     * A criterion can accept a state that breaks the law: the seed's absolute
     * residual weighs a stick point's slip by r_t, so with a tiny r_t a slipping
     * point with no traction is "converged" as stick.
     */
    template <int dim> class FrictionLawCheck
    {
    public:
      /** The fraction of the largest displacement a multiplier equation may miss by. */
      static constexpr double length_tolerance = 1e-4;

      /** @param largest_displacement max |u| over this rank (the scale of the lengths) */
      explicit FrictionLawCheck(const double largest_displacement);

      /**
       * @brief Record one multiplier equation's residual as a length.
       * @param normal whether it is a λ_n row (else a Λ row)
       */
      void
      add_multiplier_row(bool normal, double length);

      /** @brief Record |t_t| and s(λ_n) at a contact point in contact at @p where. */
      void
      add_point(const Point<dim> &where, double traction, double threshold);

      /**
       * @brief Collective: count the multiplier equations and points that break
       * the law over all ranks (the traction allowed @p traction_tolerance of
       * the largest threshold) and compose report(). Returns that count.
       */
      unsigned int
      gather(const MPI_Comm communicator, const double traction_tolerance);

      /** @brief What broke the law and by how much; empty if nothing did. */
      const std::string &
      report() const;

    private:
      double              length_scale;
      double              largest_threshold = 0.;
      std::vector<double> gap_lengths, slip_lengths, traction_excesses;
      /** the largest traction excess on this rank and where */
      double      worst_excess = 0.;
      Point<dim>  worst_excess_at;
      std::string text;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
