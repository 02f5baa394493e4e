#include <deal.II/base/patterns.h>

#include <stabilized_lagrangian/contact/friction_law.h>

#include <algorithm>

namespace StabilizedLagrangian
{
  namespace FrictionLaws
  {
    /** @brief Coulomb friction, s = μ max(λ_n, 0); frictionless when μ = 0. */
    class Coulomb : public Interface
    {
    public:
      /** @param section the law's subsection, for messages */
      Coulomb(const double mu, const std::string &section)
          : mu(mu)
      {
        if (!(mu >= 0.))
          throw InputError(section + "/Friction coefficient must be >= 0, got " +
                           std::to_string(mu) + ".");
      }

      Coulomb(const ParameterHandler &prm, const std::string &section)
          : Coulomb(prm.get_double("Friction coefficient"), section)
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry("Friction coefficient",
                          "0.1",
                          Patterns::Double(),
                          "Coulomb coefficient μ >= 0; 0 means frictionless (no friction "
                          "unknowns, no friction loop).");
      }

      bool
      has_friction() const override
      {
        return mu > 0.;
      }

      double
      threshold(const double contact_pressure) const override
      {
        return mu * std::max(contact_pressure, 0.);
      }

      double
      threshold_derivative(const double contact_pressure) const override
      {
        return contact_pressure > 0. ? mu : 0.;
      }

      bool
      threshold_depends_on_pressure() const override
      {
        return true;
      }

    private:
      const double mu;
    };

    /** @brief Tresca friction: a fixed threshold s wherever the point is in contact. */
    class Tresca : public Interface
    {
    public:
      /** @param section the law's subsection, for messages */
      Tresca(const double s, const std::string &section)
          : s(s)
      {
        if (!(s >= 0.))
          throw InputError(section + "/Threshold must be >= 0.");
      }

      Tresca(const ParameterHandler &prm, const std::string &section)
          : Tresca(prm.get_double("Threshold"), section)
      {
      }

      static void
      declare_parameters(ParameterHandler &prm)
      {
        prm.declare_entry(
            "Threshold", "10", Patterns::Double(), "Friction threshold s >= 0 (MPa).");
      }

      bool
      has_friction() const override
      {
        return s > 0.;
      }

      double
      threshold(const double) const override
      {
        return s;
      }

      double
      threshold_derivative(const double) const override
      {
        return 0.;
      }

      bool
      threshold_depends_on_pressure() const override
      {
        return false;
      }

    private:
      const double s;
    };

    SL_REGISTER_PLUGIN(Interface, Coulomb, "Coulomb", "Coulomb friction, threshold μ λ_n");
    SL_REGISTER_PLUGIN(Interface, Tresca, "Tresca", "Tresca friction, fixed threshold");
  } // namespace FrictionLaws
} // namespace StabilizedLagrangian
