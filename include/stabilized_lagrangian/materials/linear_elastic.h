#pragma once

#include <stabilized_lagrangian/materials/material.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /**
     * @brief Isotropic linear elasticity in small strain (plane strain in 2D).
     *
     * σ = λ tr(ε) I + 2G ε with ε = sym(∇u).
     */
    template <int dim> class LinearElastic : public Interface<dim>
    {
    public:
      /**
       * @param youngs_modulus E > 0 (MPa)
       * @param poissons_ratio ν in [0, 0.5)
       */
      LinearElastic(const double       youngs_modulus,
                    const double       poissons_ratio,
                    const std::string &section = "Material/linear elastic");

      /**
       * @brief Model from its `.prm` subsection (declare_parameters()), whose
       * path @p section the messages name.
       */
      LinearElastic(const ParameterHandler &prm, const std::string &section);

      /** @brief Declare `Young's modulus` and `Poisson's ratio`. */
      static void
      declare_parameters(ParameterHandler &prm);

      Response<3>
      evaluate_3d(const Tensor<2, 3>            &grad_u,
                  const ArrayView<const double> &old_history,
                  const ArrayView<double>       &new_history) const override;

      bool
      is_finite_strain() const override
      {
        return false;
      }

      double
      youngs_modulus() const override
      {
        return E;
      }

      double
      poissons_ratio() const override
      {
        return nu;
      }

    private:
      const double E;
      const double nu;
      Tensor<4, 3> elasticity;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
