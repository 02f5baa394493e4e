#pragma once

#include <stabilized_lagrangian/plugins.h>

namespace StabilizedLagrangian
{
  namespace FrictionLaws
  {
    using namespace dealii;

    /**
     * @brief Interface of the friction laws: the threshold s as a function of the
     * contact pressure. With s frozen the problem is a Tresca problem (doc/formulation.md,
     * "Nested loops").
     */
    class Interface
    {
    public:
      virtual ~Interface() = default;

      /**
       * @brief False for a frictionless law: then there are no friction unknowns
       * and no friction loop.
       */
      virtual bool
      has_friction() const = 0;

      /** @brief Friction threshold s for a contact pressure λ_n (MPa). */
      virtual double
      threshold(const double contact_pressure) const = 0;

      /** @brief ds/dλ_n, for the generalized Newton that linearises the threshold. */
      virtual double
      threshold_derivative(const double contact_pressure) const = 0;

      /** @brief True when the threshold depends on the pressure (a friction loop is needed). */
      virtual bool
      threshold_depends_on_pressure() const = 0;
    };

    /** @brief The registry of friction laws. */
    using Registry = PluginRegistry<Interface>;

    /** @brief Declare the `Friction law` subsection. */
    inline void
    declare_parameters(ParameterHandler &prm)
    {
      Registry::declare_parameters_in(
          prm, "Friction law", "Coulomb", "Friction law on the contact boundary.");
    }

    /**
     * @brief Build the friction law chosen in the `Friction law` subsection of
     * the current subsection, whose path is @p path (`Contact`, `Contact/Zone <name>`).
     */
    inline std::unique_ptr<Interface>
    create(ParameterHandler &prm, const std::string &path)
    {
      return Registry::create_from(prm, "Friction law", path);
    }
  } // namespace FrictionLaws
} // namespace StabilizedLagrangian
