#include <stabilized_lagrangian/materials/neo_hookean.h>
#include <stabilized_lagrangian/materials/parameter_checks.h>
#include <stabilized_lagrangian/materials/tensor_functions.h>

#include <cmath>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    template <int dim>
    NeoHookean<dim>::NeoHookean(const double       c10,
                                const double       poissons_ratio,
                                const std::string &section)
        : nu(poissons_ratio)
        , shear_modulus(2. * c10)
        , lame_lambda(2. * shear_modulus * nu / (1. - 2. * nu))
    {
      require_positive(c10, section + "/C10");
      require_poissons_ratio(nu, section + "/Poisson's ratio");
    }

    template <int dim>
    NeoHookean<dim>::NeoHookean(const ParameterHandler &prm, const std::string &section)
        : NeoHookean(prm.get_double("C10"), prm.get_double("Poisson's ratio"), section)
    {
    }

    template <int dim>
    void
    NeoHookean<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("C10",
                        "100",
                        Patterns::Double(),
                        "C10 = μ/2 in MPa (μ: shear modulus of the linearised response); "
                        "must be > 0.");
      prm.declare_entry("Poisson's ratio",
                        "0.4",
                        Patterns::Double(),
                        "Poisson's ratio of the linearised response; must be in [0, 0.5).");
    }

    template <int dim>
    Response<3>
    NeoHookean<dim>::evaluate_3d(const Tensor<2, 3> &grad_u,
                                 const ArrayView<const double> &,
                                 const ArrayView<double> &) const
    {
      const Tensor<2, 3> F     = deformation_gradient(grad_u);
      const double       J     = admissible_jacobian(F, "neo-Hookean");
      const Tensor<2, 3> F_inv = invert(F);
      const double       log_J = std::log(J);

      Tensor<2, 3> P =
          shear_modulus * (F - transpose(F_inv)) + lame_lambda * log_J * transpose(F_inv);
      Tensor<4, 3> A;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              A[i][j][k][l] = shear_modulus * (i == k) * (j == l) +
                              (shear_modulus - lame_lambda * log_J) * F_inv[l][i] * F_inv[j][k] +
                              lame_lambda * F_inv[j][i] * F_inv[l][k];

      return Response<3>{P, A};
    }

    template class NeoHookean<2>;
    template class NeoHookean<3>;

    SL_REGISTER_PLUGIN(
        Interface,
        NeoHookean,
        "neo-Hookean",
        "compressible neo-Hookean hyperelasticity, finite strain (plane strain in 2D)");
  } // namespace Materials
} // namespace StabilizedLagrangian
