#pragma once

#include <stabilized_lagrangian/plugins.h>

#include <string>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /**
     * @brief Throw InputError("<entry_path> must be > 0, got <value>.")
     * unless @p value > 0.
     * @param value the parsed value
     * @param entry_path full path of the entry, e.g. "Material/neo-Hookean/C10"
     */
    inline void
    require_positive(const double value, const std::string &entry_path)
    {
      if (!(value > 0.))
        throw InputError(entry_path + " must be > 0, got " + std::to_string(value) + ".");
    }

    /**
     * @brief Throw InputError unless the Poisson's ratio @p nu is in [0, 0.5)
     * (a positive definite isotropic elasticity with ν ≥ 0).
     * @param nu the parsed value
     * @param entry_path full path of the entry
     */
    inline void
    require_poissons_ratio(const double nu, const std::string &entry_path)
    {
      if (!(nu >= 0. && nu < 0.5))
        throw InputError(entry_path + " must be in [0, 0.5), got " + std::to_string(nu) + ".");
    }
  } // namespace Materials
} // namespace StabilizedLagrangian
