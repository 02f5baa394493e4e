#pragma once

#include <string>
#include <utility>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /**
     * @brief Isotropic hardening from a tabulated traction curve: yield
     * stress σ_y as a function of the equivalent plastic strain α.
     *
     * The table holds points (α_i, σ_y,i) with α_0 = 0, strictly increasing
     * α_i and non-decreasing σ_y,i > 0. σ_y is interpolated linearly between
     * the points; beyond the last point it is extrapolated with the slope of
     * the last segment (a constant σ_y if that slope is zero, and σ_y,0 for
     * a table of one point: perfect plasticity). The slope H = dσ_y/dα is that
     * of the segment [α_i, α_{i+1}) that contains α (right derivative at the
     * table points).
     */
    class HardeningCurve
    {
    public:
      /**
       * @brief Curve through the given points.
       * @param points (equivalent plastic strain, yield stress) pairs;
       * throws InputError naming @p entry_path if they do not satisfy the
       * conditions above
       * @param entry_path the parameter the points come from, for messages
       */
      HardeningCurve(const std::vector<std::pair<double, double>> &points,
                     const std::string &entry_path = "Material/J2 plasticity/Hardening curve");

      /**
       * @brief Parse "α_0:σ_0, α_1:σ_1, ..." into points (in the given order);
       * throws InputError naming @p entry_path on a syntax error.
       */
      static std::vector<std::pair<double, double>>
      parse(const std::string &text,
            const std::string &entry_path = "Material/J2 plasticity/Hardening curve");

      /** @brief Yield stress σ_y(α). */
      double
      yield_stress(const double alpha) const;

      /** @brief Hardening modulus H(α) = dσ_y/dα (right derivative). */
      double
      hardening_modulus(const double alpha) const;

      /** @brief Initial yield stress σ_y(0). */
      double
      initial_yield_stress() const
      {
        return points.front().second;
      }

    private:
      /** Index i of the segment [α_i, α_{i+1}) holding α (extended past the ends). */
      unsigned int
      segment(const double alpha) const;

      std::vector<std::pair<double, double>> points;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
