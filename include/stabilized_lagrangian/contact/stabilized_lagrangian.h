#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

namespace StabilizedLagrangian
{
  /**
   * Point-wise ingredients of the stabilized Lagrangian (doc/formulation.md,
   * "Signs and notation" and "Point-wise quantities"; seed eqs. (3)–(8)),
   * written once and used by every loop and by the output.
   */
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief Constants of the automatic augmentation parameters
     * r_n = C_n E/h and r_t = C_t/ℓ, with h the largest face diameter on Γc and
     * ℓ the largest prescribed displacement increment of a nominal load step
     * (the slip a step can produce): the robustness study (doc/robustness.md)
     * finds r_n without influence over many decades, and the good r_t band
     * set by r_t ℓ, not by μ/h.
     */
    constexpr double automatic_r_n_constant = 1.;
    constexpr double automatic_r_t_constant = 0.03;

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
     * @brief Generalized derivative of P_B: I inside the ball, (I − v̂⊗v̂)/|v| on
     * and outside it.
     *
     * On the sphere |v| = 1 both are generalized derivatives; the slip one is
     * taken, up to round-off, because a point that slipped in the previous load
     * step starts the next one there (Δs = 0, |Λ| = 1): with the stick
     * derivative the first Newton iterations of every step would hold it.
     */
    template <int n>
    Tensor<2, n>
    project_on_unit_ball_derivative(const Tensor<1, n> &v)
    {
      const double norm       = v.norm();
      Tensor<2, n> derivative = unit_symmetric_tensor<n>();
      if (norm >= 1. - 1e-10)
        {
          const Tensor<1, n> direction = v / norm;
          derivative                   = (derivative - outer_product(direction, direction)) / norm;
        }
      return derivative;
    }

    /** @brief Contact status of a point as written to the output: 0 open, 1 stick, 2 slip. */
    enum class Status : unsigned int
    {
      open  = 0,
      stick = 1,
      slip  = 2
    };

    /**
     * @brief The stabilized Lagrangian at one contact point for a given contact
     * status χ and friction threshold s (doc/formulation.md, "Residual"): the
     * tractions it applies to the slave, the residuals of the multiplier
     * equations, and the coefficients of their Jacobian. The assembly only
     * contracts these with shape functions.
     *
     * The nested fixed points freeze χ and s; the generalized Newton evaluates
     * them at the current iterate, which gives the same coefficients (χ is
     * piecewise constant) plus, when s = s(λ_n) is linearised, the derivative
     * of the tangential traction with respect to λ_n.
     *
     * @tparam n number of tangential components, dim − 1
     */
    template <int n> class PointResponse
    {
    public:
      /**
       * @param contact_pressure λ_n at the point
       * @param gap g_n with the frozen pairing
       * @param semi_multiplier Λ in the tangent basis
       * @param slip_increment Δs over the load step in the tangent basis
       * @param in_contact frozen status χ
       * @param threshold frozen friction threshold s
       * @param has_friction whether the law has friction unknowns at all
       * @param threshold_slope ds/dλ_n when the threshold is linearised, else 0
       */
      PointResponse(const double        contact_pressure,
                    const double        gap,
                    const Tensor<1, n> &semi_multiplier,
                    const Tensor<1, n> &slip_increment,
                    const bool          in_contact,
                    const double        threshold,
                    const bool          has_friction,
                    const double        r_n,
                    const double        r_t,
                    const double        threshold_slope = 0.)
          : chi(in_contact ? 1. : 0.)
          , chi_f((has_friction && in_contact && threshold > 0.) ? 1. : 0.)
          , s(threshold)
          , ds(threshold_slope)
          , r_n(r_n)
          , r_t(r_t)
          , lambda(contact_pressure)
          , gap_value(gap)
          , semi(semi_multiplier)
          , lambda_hat(augmented_pressure(contact_pressure, gap, r_n))
          , g_hat(augmented_semi_multiplier(semi_multiplier, slip_increment, r_t))
          , projected(project_on_unit_ball(g_hat))
          , d_projected(project_on_unit_ball_derivative(g_hat))
      {
      }

      /** @brief Normal pressure on the slave, χ λ̂ (the force along n). */
      double
      normal_traction() const
      {
        return chi * lambda_hat;
      }

      /** @brief Tangential traction on the slave, −χ_f s P_B(ĝ), tangent basis. */
      Tensor<1, n>
      tangential_traction() const
      {
        return -chi_f * s * projected;
      }

      /** @brief Residual of the λ_n equation per test function: −[(1−χ) λ_n / r_n + χ g_n]. */
      double
      pressure_residual() const
      {
        return -((1. - chi) * lambda / r_n + chi * gap_value);
      }

      /**
       * @brief Residual of the Λ equation per test function,
       * −[χ_f (s/r_t)(Λ − P_B(ĝ)) + (1−χ_f) Λ] (the sign that makes the Jacobian symmetric).
       */
      Tensor<1, n>
      semi_multiplier_residual() const
      {
        return -(chi_f * (s / r_t) * (semi - projected) + (1. - chi_f) * semi);
      }

      /**
       * @brief The factor that turns the Λ equation into a length: χ_f s + (1 − χ_f) r_t.
       * The residual divided by it is (Λ − P_B(ĝ))/r_t in contact, which is −Δs
       * at a stick point, and Λ/r_t off contact: the length that moves ĝ by the
       * mismatch. (The λ_n equation is a length already: g_n, or λ_n/r_n off contact.)
       */
      double
      semi_multiplier_weight() const
      {
        return chi_f * s + (1. - chi_f) * r_t;
      }
      /** @brief ∂(normal force)/∂g_n·(−1): the stiffness χ r_n of the u–u block along n. */
      double
      normal_stiffness() const
      {
        return chi * r_n;
      }

      /** @brief The u–u block along the tangents, χ_f s r_t dP_B. */
      Tensor<2, n>
      tangential_stiffness() const
      {
        return chi_f * s * r_t * d_projected;
      }

      /** @brief The u–λ_n coupling per unit normal shape, −χ. */
      double
      pressure_coupling() const
      {
        return -chi;
      }

      /** @brief The u–Λ coupling per unit tangential shape, χ_f s dP_B. */
      Tensor<2, n>
      friction_coupling() const
      {
        return chi_f * s * d_projected;
      }

      /** @brief ∂(tangential traction)/∂λ_n, −χ_f (ds/dλ_n) P_B(ĝ); zero with s frozen. */
      Tensor<1, n>
      tangential_traction_pressure_derivative() const
      {
        return -chi_f * ds * projected;
      }

      /** @brief The λ_n–λ_n block, −(1−χ)/r_n. */
      double
      pressure_compliance() const
      {
        return -(1. - chi) / r_n;
      }

      /** @brief The Λ–Λ block, −[χ_f (s/r_t)(I − dP_B) + (1−χ_f) I]. */
      Tensor<2, n>
      semi_multiplier_block() const
      {
        const Tensor<2, n> identity = unit_symmetric_tensor<n>();
        return -(chi_f * (s / r_t) * (identity - d_projected) + (1. - chi_f) * identity);
      }

      /** @brief λ_n. */
      double
      pressure() const
      {
        return lambda;
      }

      /**
       * @brief The residual of the λ_n equation with the status of this point
       * and the gap @p gap of another: −[(1−χ) λ_n / r_n + χ g]. With weighted
       * complementarity a node's status and λ_n hold on its whole support,
       * where each integration point brings its own gap.
       */
      double
      pressure_residual_at(const double gap) const
      {
        return -((1. - chi) * lambda / r_n + chi * gap);
      }

      /**
       * @brief The tangential traction of the multiplier itself, −χ_f s Λ:
       * at a converged node Λ = P_B(ĝ), so it is tangential_traction(); the
       * weighted formulation lets the displacement see it (linear in Λ).
       */
      Tensor<1, n>
      multiplier_traction() const
      {
        return -chi_f * s * semi;
      }

      /** @brief ∂(multiplier_traction())/∂λ_n, −χ_f (ds/dλ_n) Λ; zero with s frozen. */
      Tensor<1, n>
      multiplier_traction_pressure_derivative() const
      {
        return -chi_f * ds * semi;
      }

      /** @brief χ_f s: −∂(multiplier_traction())/∂Λ per component. */
      double
      friction_factor() const
      {
        return chi_f * s;
      }

      /** @brief Open, stick (friction active, |ĝ| ≤ 1) or slip (frictionless contact slips). */
      Status
      status() const
      {
        if (chi == 0.)
          return Status::open;
        return (chi_f > 0. && is_sticking(g_hat)) ? Status::stick : Status::slip;
      }

    private:
      const double       chi, chi_f, s, ds, r_n, r_t;
      const double       lambda, gap_value;
      const Tensor<1, n> semi;
      const double       lambda_hat;
      const Tensor<1, n> g_hat, projected;
      const Tensor<2, n> d_projected;
    };
  } // namespace Contact
} // namespace StabilizedLagrangian
