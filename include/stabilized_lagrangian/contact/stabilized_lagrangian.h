#pragma once

#include <deal.II/base/tensor.h>

namespace StabilizedLagrangian
{
  /**
   * Point-wise ingredients of the stabilized Lagrangian (DESIGN §2, seed
   * eqs. (3)–(8)), written once and used by every loop and by the output.
   */
  namespace Contact
  {
    using namespace dealii;

    /** @brief Augmented pressure λ̂ = λ_n − r_n g_n (compression positive). */
    inline double
    augmented_pressure(const double contact_pressure, const double gap, const double r_n)
    {
      return contact_pressure - r_n * gap;
    }

    /**
     * @brief Contact status χ of seed eq. (5): in contact when λ̂ ≥ 0.
     *
     * The seed counts λ̂ = 0 as contact, so points that touch with no pressure
     * yet (a body resting on the obstacle at the first step) start in contact,
     * which load-controlled scenes need to be well posed.
     */
    inline bool
    is_in_contact(const double augmented_pressure)
    {
      return augmented_pressure >= 0.;
    }

    /** @brief Augmented semi-multiplier ĝ = Λ + r_t Δs. */
    template <int n>
    Tensor<1, n>
    augmented_semi_multiplier(const Tensor<1, n> &semi_multiplier,
                              const Tensor<1, n> &slip_increment,
                              const double        r_t)
    {
      return semi_multiplier + r_t * slip_increment;
    }

    /** @brief Stick test of seed eq. (8): |ĝ| ≤ 1. */
    template <int n>
    bool
    is_sticking(const Tensor<1, n> &augmented_semi_multiplier)
    {
      return augmented_semi_multiplier.norm() <= 1.;
    }

    /** @brief Projection onto the unit ball, P_B(v) = v if |v| ≤ 1, else v/|v|. */
    template <int n>
    Tensor<1, n>
    project_on_unit_ball(const Tensor<1, n> &v)
    {
      const double norm = v.norm();
      return norm <= 1. ? v : v / norm;
    }

    /**
     * @brief Generalized derivative of P_B: I in the ball, (I − v̂⊗v̂)/|v| outside.
     */
    template <int n>
    Tensor<2, n>
    project_on_unit_ball_derivative(const Tensor<1, n> &v)
    {
      const double norm       = v.norm();
      Tensor<2, n> derivative = unit_symmetric_tensor<n>();
      if (norm > 1.)
        {
          const Tensor<1, n> direction = v / norm;
          derivative                   = (derivative - outer_product(direction, direction)) / norm;
        }
      return derivative;
    }
  } // namespace Contact
} // namespace StabilizedLagrangian
