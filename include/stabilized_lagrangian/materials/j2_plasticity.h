#pragma once

#include <deal.II/base/symmetric_tensor.h>

#include <stabilized_lagrangian/materials/hardening_curve.h>
#include <stabilized_lagrangian/materials/material.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    /** @brief Kinematics of a model: infinitesimal strain or finite strain. */
    enum class Kinematics
    {
      small_strain,
      finite_strain
    };

    /**
     * @brief J2 (von Mises) elasto-plasticity with isotropic hardening from a
     * tabulated traction curve; radial return and consistent tangent (plane
     * strain in 2D, computed in 3D with the out-of-plane strain held at zero).
     *
     * The return map is one and the same for both kinematics: given a trial
     * elastic strain ε_tr and the equivalent plastic strain α_n, with
     * s_tr = 2G dev ε_tr, n = s_tr/|s_tr| and
     *   f = |s_tr| − √(2/3) σ_y(α),
     * a plastic step solves (Simo & Hughes, Box 3.1)
     *   |s_tr| − 2G Δγ − √(2/3) σ_y(α_n + √(2/3) Δγ) = 0
     * for Δγ by Newton's method safeguarded by bisection, and the stress is
     * K tr ε_tr 1 + s_tr − 2G Δγ n, with the algorithmic tangent (Box 3.2,
     * H = dσ_y/dα of the current segment of the table)
     *   D = K 1⊗1 + 2Gθ (I − ⅓ 1⊗1) − 2G θ̄ n⊗n,
     *   θ = 1 − 2GΔγ/|s_tr|,  θ̄ = 1/(1 + H/(3G)) − (1 − θ).
     *
     * - Small strain: ε_tr = sym ∇u − ε_p,n, and the stress is the Cauchy
     *   stress. History: ε_p (6 components) and α.
     * - Finite strain: multiplicative plasticity F = F_e F_p with the
     *   logarithmic elastic strain (Simo 1992; de Souza Neto, Perić & Owen,
     *   ch. 14): b_e,tr = F C_p,n^{-1} Fᵀ, ε_tr = ½ ln b_e,tr, the return
     *   map above gives the Kirchhoff stress τ (the hardening curve is then
     *   read as Kirchhoff stress against equivalent logarithmic plastic
     *   strain), P = τ F^{-T}, b_e = exp(2 ε_e), C_p^{-1} = F^{-1} b_e F^{-T}.
     *   The tangent is analytic: with L = ∂ ln b / ∂b at b_e,tr and
     *   B_ijkl = δ_ik b_jl + δ_jk b_il,
     *     a_ijkl = ½ (D : L : B)_ijkl − τ_il δ_jk,
     *     ∂P_iJ/∂F_kL = a_ijkl F^{-1}_Jj F^{-1}_Ll
     *   (J times the spatial modulus of the Cauchy form). History: C_p^{-1} (6 components,
     * initially the identity) and α.
     *
     * History layout: the symmetric tensor (ε_p or C_p^{-1}) in the order
     * xx, yy, zz, xy, xz, yz (tensor components, not engineering shears),
     * then α. In plane strain the zz component evolves as well.
     */
    template <int dim> class J2Plasticity : public Interface<dim>
    {
    public:
      /** Position of the equivalent plastic strain α in the history. */
      static constexpr unsigned int equivalent_plastic_strain_index = 6;

      /**
       * @brief Model with the given elastic constants, kinematics and
       * traction curve.
       * @param youngs_modulus E > 0 (MPa)
       * @param poissons_ratio ν in [0, 0.5)
       * @param kinematics small or finite strain
       * @param hardening_points (equivalent plastic strain, yield stress)
       * pairs of the traction curve (see HardeningCurve); throws InputError if
       * any of the parameters is out of range
       * @param section the model's subsection, for messages
       */
      J2Plasticity(const double                                  youngs_modulus,
                   const double                                  poissons_ratio,
                   const Kinematics                              kinematics,
                   const std::vector<std::pair<double, double>> &hardening_points,
                   const std::string &section = "Material/J2 plasticity");

      /**
       * @brief Model from its `.prm` subsection (declare_parameters()), whose
       * path @p section the messages name.
       */
      J2Plasticity(const ParameterHandler &prm, const std::string &section);

      /**
       * @brief Declare `Young's modulus`, `Poisson's ratio`, `Kinematics` and
       * `Hardening curve`.
       */
      static void
      declare_parameters(ParameterHandler &prm);

      /**
       * @brief Stress, consistent tangent and updated history by radial return.
       *
       * Finite strain throws InadmissibleState if J = det F is not a
       * positive number. @p new_history is written on every call.
       */
      Response<3>
      evaluate_3d(const Tensor<2, 3>            &grad_u,
                  const ArrayView<const double> &old_history,
                  const ArrayView<double>       &new_history) const override;

      /** @brief Seven: a symmetric tensor (ε_p or C_p^{-1}) and α. */
      unsigned int
      n_history() const override
      {
        return 7;
      }

      /** @brief ε_p = 0 (small strain) or C_p^{-1} = I (finite strain), α = 0. */
      void
      initial_history(const ArrayView<double> &history) const override;

      /** @brief The equivalent plastic strain α is shown in the output. */
      std::vector<std::string>
      history_field_names() const override
      {
        return {"equivalent_plastic_strain"};
      }

      /** @brief α from @p history. */
      std::vector<double>
      history_fields(const ArrayView<const double> &history) const override
      {
        return {history[equivalent_plastic_strain_index]};
      }

      /** @brief Whether `Kinematics` is finite strain. */
      bool
      is_finite_strain() const override
      {
        return kinematics == Kinematics::finite_strain;
      }

      /** @brief Young's modulus E. */
      double
      youngs_modulus() const override
      {
        return E;
      }

      /** @brief Poisson's ratio ν. */
      double
      poissons_ratio() const override
      {
        return nu;
      }

    private:
      /** Result of the return map for one trial elastic strain. */
      struct ReturnMap
      {
        /** Cauchy (small strain) or Kirchhoff (finite strain) stress. */
        SymmetricTensor<2, 3> stress;
        /** Plastic strain increment Δγ n. */
        SymmetricTensor<2, 3> plastic_strain_increment;
        /** Whether the step is plastic (Δγ > 0). */
        bool plastic;
        /** Updated equivalent plastic strain. */
        double equivalent_plastic_strain;
        /** Algorithmic tangent ∂stress/∂ε_tr. */
        SymmetricTensor<4, 3> tangent;
      };

      /** Radial return from a trial elastic strain (the class documentation). */
      ReturnMap
      radial_return(const SymmetricTensor<2, 3> &trial_elastic_strain,
                    const double                 old_equivalent_plastic_strain) const;

      /** evaluate_3d() with ε = sym ∇u and the history ε_p, α. */
      Response<3>
      evaluate_small_strain(const Tensor<2, 3>            &grad_u,
                            const ArrayView<const double> &old_history,
                            const ArrayView<double>       &new_history) const;

      /** evaluate_3d() with F = I + ∇u and the history C_p^{-1}, α. */
      Response<3>
      evaluate_finite_strain(const Tensor<2, 3>            &grad_u,
                             const ArrayView<const double> &old_history,
                             const ArrayView<double>       &new_history) const;

      const double         E;
      const double         nu;
      const Kinematics     kinematics;
      const HardeningCurve hardening;
      const double         bulk_modulus;
      const double         shear_modulus;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
