#include <stabilized_lagrangian/materials/j2_plasticity.h>
#include <stabilized_lagrangian/materials/linear_elastic.h>
#include <stabilized_lagrangian/materials/parameter_checks.h>
#include <stabilized_lagrangian/materials/tensor_functions.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    namespace
    {
      const double sqrt_two_thirds = std::sqrt(2. / 3.);

      /** The symmetric tensor stored in history[0..5] (order xx, yy, zz, xy, xz, yz). */
      SymmetricTensor<2, 3>
      read_tensor(const ArrayView<const double> &history)
      {
        SymmetricTensor<2, 3> t;
        for (unsigned int c = 0; c < SymmetricTensor<2, 3>::n_independent_components; ++c)
          t[SymmetricTensor<2, 3>::unrolled_to_component_indices(c)] = history[c];
        return t;
      }

      void
      write_tensor(const SymmetricTensor<2, 3> &t, const ArrayView<double> &history)
      {
        for (unsigned int c = 0; c < SymmetricTensor<2, 3>::n_independent_components; ++c)
          history[c] = t[SymmetricTensor<2, 3>::unrolled_to_component_indices(c)];
      }
    } // namespace

    template <int dim>
    J2Plasticity<dim>::J2Plasticity(const double                                  youngs_modulus,
                                    const double                                  poissons_ratio,
                                    const Kinematics                              kinematics,
                                    const std::vector<std::pair<double, double>> &hardening_points,
                                    const std::string                            &section)
        : E(youngs_modulus)
        , nu(poissons_ratio)
        , kinematics(kinematics)
        , hardening(hardening_points, section + "/Hardening curve")
        , bulk_modulus(E / (3. * (1. - 2. * nu)))
        , shear_modulus(E / (2. * (1. + nu)))
    {
      require_positive(E, section + "/Young's modulus");
      require_poissons_ratio(nu, section + "/Poisson's ratio");
    }

    template <int dim>
    J2Plasticity<dim>::J2Plasticity(const ParameterHandler &prm, const std::string &section)
        : J2Plasticity(
              prm.get_double("Young's modulus"),
              prm.get_double("Poisson's ratio"),
              prm.get("Kinematics") == "finite strain" ? Kinematics::finite_strain
                                                       : Kinematics::small_strain,
              HardeningCurve::parse(prm.get("Hardening curve"), section + "/Hardening curve"),
              section)
    {
    }

    template <int dim>
    void
    J2Plasticity<dim>::declare_parameters(ParameterHandler &prm)
    {
      // the elastic constants are those of linear elasticity
      LinearElastic<dim>::declare_parameters(prm);
      prm.declare_entry("Kinematics",
                        "small strain",
                        Patterns::Selection("small strain|finite strain"),
                        "'small strain': additive split of ε = sym ∇u, Cauchy stress. "
                        "'finite strain': multiplicative split F = F_e F_p with the "
                        "logarithmic elastic strain ½ ln b_e and the Kirchhoff stress.");
      prm.declare_entry(
          "Hardening curve",
          "0:194, 0.01:240, 0.05:290, 0.1:320, 0.2:350, 0.5:390, 1:420",
          Patterns::Map(Patterns::Double(), Patterns::Double(), 1),
          "Traction curve as 'equivalent plastic strain:yield stress' pairs (MPa) separated by "
          "','. The first plastic strain must be 0, the strains strictly increasing, the yield "
          "stresses > 0 and non-decreasing. Interpolated linearly; beyond the last point "
          "extrapolated with the slope of the last segment. In finite strain the yield stress is "
          "a Kirchhoff stress and the plastic strain logarithmic.");
    }

    template <int dim>
    void
    J2Plasticity<dim>::initial_history(const ArrayView<double> &history) const
    {
      AssertDimension(history.size(), n_history());
      write_tensor(is_finite_strain() ? unit_symmetric_tensor<3>() : SymmetricTensor<2, 3>(),
                   history);
      history[equivalent_plastic_strain_index] = 0.;
    }

    namespace
    {
      /** relative distance to the yield surface within which a state counts as elastic */
      constexpr double yield_surface_tolerance = 1e-10;
    } // namespace

    template <int dim>
    typename J2Plasticity<dim>::ReturnMap
    J2Plasticity<dim>::radial_return(const SymmetricTensor<2, 3> &trial_elastic_strain,
                                     const double old_equivalent_plastic_strain) const
    {
      const double                G              = shear_modulus;
      const SymmetricTensor<2, 3> trial_deviator = 2. * G * deviator(trial_elastic_strain);
      const double                trial_norm     = trial_deviator.norm();
      const double                mean_stress    = bulk_modulus * trace(trial_elastic_strain);
      const SymmetricTensor<2, 3> one            = unit_symmetric_tensor<3>();

      ReturnMap result;
      result.plastic                   = false;
      result.equivalent_plastic_strain = old_equivalent_plastic_strain;
      result.tangent = bulk_modulus * outer_product(one, one) + 2. * G * deviator_tensor<3>();
      result.stress  = mean_stress * one + trial_deviator;

      const auto consistency = [&](const double delta_gamma) {
        return trial_norm - 2. * G * delta_gamma -
               sqrt_two_thirds * hardening.yield_stress(old_equivalent_plastic_strain +
                                                        sqrt_two_thirds * delta_gamma);
      };
      // A point that yielded in the previous step starts the next one on the
      // yield surface, where round-off alone would decide elastic or plastic
      // (and the tangent of the first Newton step): within 1e-10 of the yield
      // stress it is elastic, whatever the rounding.
      if (consistency(0.) <=
          yield_surface_tolerance * hardening.yield_stress(old_equivalent_plastic_strain))
        return result;

      // Newton on Δγ, kept inside the bracket [lower, upper] where the
      // consistency function (decreasing in Δγ) changes sign; with piecewise
      // linear hardening Newton is exact once it is on the right segment.
      double       delta_gamma = 0.;
      double       lower = 0., upper = trial_norm / (2. * G);
      const double tolerance = 1e-14 * trial_norm;
      for (unsigned int iteration = 0;; ++iteration)
        {
          const double residual = consistency(delta_gamma);
          if (std::abs(residual) <= tolerance)
            break;
          AssertThrow(iteration < 200,
                      ExcMessage("J2 plasticity: the return map did not converge."));
          (residual > 0. ? lower : upper) = delta_gamma;
          const double slope =
              -2. * G - 2. / 3. *
                            hardening.hardening_modulus(old_equivalent_plastic_strain +
                                                        sqrt_two_thirds * delta_gamma);
          delta_gamma -= residual / slope;
          if (!(delta_gamma > lower && delta_gamma < upper))
            delta_gamma = 0.5 * (lower + upper);
        }

      const SymmetricTensor<2, 3> flow_direction = trial_deviator / trial_norm;
      result.plastic                             = true;
      result.equivalent_plastic_strain += sqrt_two_thirds * delta_gamma;
      result.plastic_strain_increment = delta_gamma * flow_direction;
      result.stress -= 2. * G * delta_gamma * flow_direction;

      // Simo & Hughes, Box 3.2
      const double H         = hardening.hardening_modulus(result.equivalent_plastic_strain);
      const double theta     = 1. - 2. * G * delta_gamma / trial_norm;
      const double theta_bar = 1. / (1. + H / (3. * G)) - (1. - theta);
      result.tangent         = bulk_modulus * outer_product(one, one) +
                       2. * G * theta * deviator_tensor<3>() -
                       2. * G * theta_bar * outer_product(flow_direction, flow_direction);
      return result;
    }

    template <int dim>
    Response<3>
    J2Plasticity<dim>::evaluate_3d(const Tensor<2, 3>            &grad_u,
                                   const ArrayView<const double> &old_history,
                                   const ArrayView<double>       &new_history) const
    {
      AssertDimension(old_history.size(), n_history());
      AssertDimension(new_history.size(), n_history());
      return is_finite_strain() ? evaluate_finite_strain(grad_u, old_history, new_history)
                                : evaluate_small_strain(grad_u, old_history, new_history);
    }

    template <int dim>
    Response<3>
    J2Plasticity<dim>::evaluate_small_strain(const Tensor<2, 3>            &grad_u,
                                             const ArrayView<const double> &old_history,
                                             const ArrayView<double>       &new_history) const
    {
      const SymmetricTensor<2, 3> strain             = symmetrize(grad_u);
      const SymmetricTensor<2, 3> old_plastic_strain = read_tensor(old_history);
      const ReturnMap             map =
          radial_return(strain - old_plastic_strain, old_history[equivalent_plastic_strain_index]);

      write_tensor(old_plastic_strain + map.plastic_strain_increment, new_history);
      new_history[equivalent_plastic_strain_index] = map.equivalent_plastic_strain;

      return Response<3>{map.stress, map.tangent};
    }

    template <int dim>
    Response<3>
    J2Plasticity<dim>::evaluate_finite_strain(const Tensor<2, 3>            &grad_u,
                                              const ArrayView<const double> &old_history,
                                              const ArrayView<double>       &new_history) const
    {
      const Tensor<2, 3> F = deformation_gradient(grad_u);
      admissible_jacobian(F, "J2 plasticity");
      const Tensor<2, 3> F_inv = invert(F);

      // elastic predictor in logarithmic strain, return map, and update of C_p^{-1}
      const Tensor<2, 3>          old_inverse_plastic_cauchy_green = read_tensor(old_history);
      const SymmetricTensor<2, 3> trial_elastic_left_cauchy_green =
          symmetrize(F * old_inverse_plastic_cauchy_green * transpose(F));
      const TensorLogarithm log_b = tensor_logarithm(trial_elastic_left_cauchy_green);
      const ReturnMap       map =
          radial_return(0.5 * log_b.value, old_history[equivalent_plastic_strain_index]);
      const SymmetricTensor<2, 3> &tau = map.stress;

      if (map.plastic)
        {
          const SymmetricTensor<2, 3> elastic_strain =
              0.5 * log_b.value - map.plastic_strain_increment;
          const SymmetricTensor<2, 3> elastic_left_cauchy_green =
              isotropic_function(elastic_strain, [](const double e) { return std::exp(2. * e); });
          write_tensor(symmetrize(F_inv * elastic_left_cauchy_green * transpose(F_inv)),
                       new_history);
        }
      else
        write_tensor(read_tensor(old_history), new_history);
      new_history[equivalent_plastic_strain_index] = map.equivalent_plastic_strain;

      // ∂τ/∂F_kL = ½ D : L : ∂b_e,tr/∂F_kL with ∂b_pq/∂F_kL = B_pqkr F^{-1}_Lr, and
      // ½ (M : B)_ijkl = M_ijkq b_ql for M = D : L with the minor symmetries;
      // the geometric term −τ_il δ_jk comes from ∂F^{-T}/∂F in P = τ F^{-T}.
      const SymmetricTensor<4, 3>  M = map.tangent * log_b.derivative;
      const SymmetricTensor<2, 3> &b = trial_elastic_left_cauchy_green;
      Tensor<4, 3>                 spatial_tangent;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              {
                double a_ijkl = -tau[i][l] * (j == k);
                for (unsigned int q = 0; q < 3; ++q)
                  a_ijkl += M[i][j][k][q] * b[q][l];
                spatial_tangent[i][j][k][l] = a_ijkl;
              }
      Tensor<4, 3> A;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int J = 0; J < 3; ++J)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int L = 0; L < 3; ++L)
              for (unsigned int j = 0; j < 3; ++j)
                for (unsigned int l = 0; l < 3; ++l)
                  A[i][J][k][L] += spatial_tangent[i][j][k][l] * F_inv[J][j] * F_inv[L][l];

      return Response<3>{Tensor<2, 3>(tau) * transpose(F_inv), A};
    }

    template class J2Plasticity<2>;
    template class J2Plasticity<3>;

    SL_REGISTER_PLUGIN(Interface,
                       J2Plasticity,
                       "J2 plasticity",
                       "von Mises elasto-plasticity with isotropic hardening from a tabulated "
                       "traction curve, small or finite strain (plane strain in 2D)");
  } // namespace Materials
} // namespace StabilizedLagrangian
