#include <deal.II/base/symmetric_tensor.h>

#include <stabilized_lagrangian/materials/linear_elastic.h>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    template <int dim>
    LinearElastic<dim>::LinearElastic(const double       youngs_modulus,
                                      const double       poissons_ratio,
                                      const std::string &section)
        : E(youngs_modulus)
        , nu(poissons_ratio)
    {
      if (!(E > 0.))
        throw InputError(section + "/Young's modulus must be > 0, got " + std::to_string(E) + ".");
      if (!(nu >= 0. && nu < 0.5))
        throw InputError(section + "/Poisson's ratio must be in [0, 0.5), got " +
                         std::to_string(nu) + ".");
      const double lame_lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
      const double G           = E / (2. * (1. + nu));
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              elasticity[i][j][k][l] = lame_lambda * (i == j) * (k == l) +
                                       G * ((i == k) * (j == l) + (i == l) * (j == k));
    }

    template <int dim>
    LinearElastic<dim>::LinearElastic(const ParameterHandler &prm, const std::string &section)
        : LinearElastic(
              prm.get_double("Young's modulus"), prm.get_double("Poisson's ratio"), section)
    {
    }

    template <int dim>
    void
    LinearElastic<dim>::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Young's modulus",
                        "200000",
                        Patterns::Double(),
                        "Young's modulus E in MPa; must be > 0.");
      prm.declare_entry(
          "Poisson's ratio", "0.3", Patterns::Double(), "Poisson's ratio; must be in [0, 0.5).");
    }

    template <int dim>
    Response<3>
    LinearElastic<dim>::evaluate_3d(const Tensor<2, 3> &grad_u,
                                    const ArrayView<const double> &,
                                    const ArrayView<double> &) const
    {
      return Response<3>{double_contract<2, 0, 3, 1>(elasticity, grad_u), elasticity};
    }

    template class LinearElastic<2>;
    template class LinearElastic<3>;

    SL_REGISTER_PLUGIN(Interface,
                       LinearElastic,
                       "linear elastic",
                       "isotropic linear elasticity, small strain (plane strain in 2D)");
  } // namespace Materials
} // namespace StabilizedLagrangian
