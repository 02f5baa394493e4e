#pragma once

#include <stabilized_lagrangian/materials/material.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /**
     * @brief Compressible neo-Hookean hyperelasticity, finite strain, total
     * Lagrangian (plane strain in 2D: F_33 = 1).
     *
     * Strain energy per unit reference volume, with μ = 2 C10 and
     * λ = 2μν/(1 − 2ν):
     *   W(F) = μ/2 (I1 − 3) − μ ln J + λ/2 (ln J)²,  I1 = F : F,  J = det F,
     * whose linearisation at F = I is isotropic linear elasticity with the
     * Lamé constants λ, μ, hence E = 2μ(1 + ν). Then
     *   P = ∂W/∂F = μ (F − F^{-T}) + λ ln J F^{-T},
     *   ∂P_ij/∂F_kl = μ δ_ik δ_jl + (μ − λ ln J) F^{-1}_li F^{-1}_jk
     *               + λ F^{-1}_ji F^{-1}_lk.
     */
    template <int dim> class NeoHookean : public Interface<dim>
    {
    public:
      /**
       * @brief Model with μ = 2 C10 and λ = 2μν/(1 − 2ν); throws InputError
       * if a parameter is out of range.
       * @param c10 C10 = μ/2 > 0 (MPa)
       * @param poissons_ratio ν in [0, 0.5)
       */
      NeoHookean(const double       c10,
                 const double       poissons_ratio,
                 const std::string &section = "Material/neo-Hookean");

      /**
       * @brief Model from its `.prm` subsection (declare_parameters()), whose
       * path @p section the messages name.
       */
      NeoHookean(const ParameterHandler &prm, const std::string &section);

      /** @brief Declare `C10` and `Poisson's ratio`. */
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * @brief First Piola–Kirchhoff stress and ∂P/∂F at F = I + ∇u.
       *
       * Throws InadmissibleState if J = det F is not a positive number.
       */
      Response<3>
      evaluate_3d(const Tensor<2, 3>            &grad_u,
                  const ArrayView<const double> &old_history,
                  const ArrayView<double>       &new_history) const override;

      /** @brief True: total Lagrangian finite strain. */
      bool
      is_finite_strain() const override
      {
        return true;
      }

      /** @brief E = 2μ(1 + ν) of the linearised response. */
      double
      youngs_modulus() const override
      {
        return 2. * shear_modulus * (1. + nu);
      }

      /** @brief Poisson's ratio ν. */
      double
      poissons_ratio() const override
      {
        return nu;
      }

    private:
      const double nu;
      const double shear_modulus;
      const double lame_lambda;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
