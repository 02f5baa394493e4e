// Neo-Hookean material: stress against central differences of the strain
// energy, tangent against central differences of the stress, objectivity,
// the small-strain limit (linear elasticity), plane strain against 3D,
// rejection of J ≤ 0, and construction from the parameter file.
//
// Tolerances: a central difference with step h has the error
// h²/6 |∂³f| + ε_mach |f|/h, i.e. about 1e-12 + 1e-10 relative for h = 1e-6
// at these strains (|∇u| ≤ 0.3, so the derivatives of W vary on a scale of
// O(1) in F); 1e-7 leaves a margin of two to three orders of magnitude and
// still catches any wrong term (which would be O(1) relative).

#include <stabilized_lagrangian/materials/linear_elastic.h>
#include <stabilized_lagrangian/materials/neo_hookean.h>

#include "material_test_tools.h"

using namespace MaterialTestTools;

namespace
{
  const double c10 = 100., nu = 0.4;
  const double mu = 2. * c10, lambda = 2. * mu * nu / (1. - 2. * nu);

  /** W = μ/2 (I1 − 3) − μ ln J + λ/2 (ln J)², with F_33 = 1 in plane strain. */
  template <int dim>
  double
  strain_energy(const Tensor<2, dim> &grad_u)
  {
    Tensor<2, dim> F = grad_u;
    for (unsigned int i = 0; i < dim; ++i)
      F[i][i] += 1.;
    const double I1    = scalar_product(F, F) + (dim == 2 ? 1. : 0.);
    const double log_J = std::log(determinant(F));
    return mu / 2. * (I1 - 3.) - mu * log_J + lambda / 2. * log_J * log_J;
  }

  template <int dim>
  void
  test_finite_differences()
  {
    const Materials::NeoHookean<dim> material(c10, nu);
    const MaterialPoint<dim>         point(material);
    std::mt19937                     rng(7 + dim);
    const double                     h                = 1e-6;
    double                           max_stress_error = 0., max_tangent_error = 0.;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        // |∇u| up to about 0.3
        const Tensor<2, dim> grad_u    = random_gradient<dim>(rng, 0.3 / dim);
        const Tensor<2, dim> direction = random_gradient<dim>(rng, 1.);
        const double         dW =
            (strain_energy(grad_u + h * direction) - strain_energy(grad_u - h * direction)) /
            (2. * h);
        // relative to |P| |d|, the scale of dW (dW itself may nearly vanish)
        const Tensor<2, dim> P = point.evaluate(grad_u).stress;
        const double         stress_error =
            std::abs(dW - scalar_product(P, direction)) / (P.norm() * direction.norm());
        max_stress_error  = std::max(max_stress_error, stress_error);
        max_tangent_error = std::max(max_tangent_error, tangent_error(point, grad_u, direction, h));
      }
    check_below(max_stress_error,
                1e-7,
                std::to_string(dim) +
                    "D P vs central difference of W (max relative error, 20 states)");
    check_below(max_tangent_error,
                1e-7,
                std::to_string(dim) + "D dP/dF vs central difference of P (max relative error)");
  }

  template <int dim>
  void
  test_objectivity()
  {
    const Materials::NeoHookean<dim> material(c10, nu);
    std::mt19937                     rng(11 + dim);
    const Tensor<2, dim>             grad_u = random_gradient<dim>(rng, 0.3 / dim);
    const auto [stress_error, tangent_error] =
        objectivity_errors(MaterialPoint<dim>(material), grad_u, random_rotation<dim>(rng));
    check_below(
        stress_error, 1e-12, std::to_string(dim) + "D objectivity P(QF) = Q P(F) (relative error)");
    check_below(tangent_error,
                1e-12,
                std::to_string(dim) + "D objectivity A(QF) = Q_ia Q_kb A_aJbL(F) (relative error)");
  }

  template <int dim>
  void
  test_small_strain_limit()
  {
    const Materials::NeoHookean<dim>    material(c10, nu);
    const Materials::LinearElastic<dim> linear(2. * mu * (1. + nu), nu);
    check(std::abs(material.youngs_modulus() - 2. * mu * (1. + nu)) < 1e-12 * mu,
          std::to_string(dim) + "D youngs_modulus() = 2 mu (1 + nu)",
          material.youngs_modulus());
    std::mt19937 rng(13 + dim);
    const auto [tangent_error, stress_error] =
        small_strain_limit_errors(MaterialPoint<dim>(material), MaterialPoint<dim>(linear), rng);
    check_below(tangent_error,
                1e-12,
                std::to_string(dim) +
                    "D tangent at F = I equals linear elasticity (relative error)");
    check_below(stress_error,
                1e-5,
                std::to_string(dim) + "D P at |grad u| ~ 1e-6 vs linear elasticity (relative)");
  }

  void
  test_plane_strain()
  {
    const Materials::NeoHookean<2> material_2d(c10, nu);
    const Materials::NeoHookean<3> material_3d(c10, nu);
    std::mt19937                   rng(17);
    const Tensor<2, 2>             grad_u = random_gradient<2>(rng, 0.15);
    const auto                     r2     = MaterialPoint<2>(material_2d).evaluate(grad_u);
    const auto   r3 = MaterialPoint<3>(material_3d).evaluate(Materials::embed_in_3d(grad_u));
    const double J  = determinant(Materials::deformation_gradient(grad_u));
    const double difference = plane_strain_difference(r2, r3, J);
    check_below(difference,
                1e-12 * mu,
                "2D = in-plane block of 3D with F_33 = 1, sigma_33 = P_33/J (max |difference|)");
    const double closed_form = lambda * std::log(J) / J;
    check(std::abs(r2.out_of_plane_stress - closed_form) < 1e-12 * mu && std::abs(closed_form) > 1.,
          "plane strain sigma_33 = lambda ln J / J",
          r2.out_of_plane_stress);
  }

  template <int dim>
  void
  test_inadmissible()
  {
    const Materials::NeoHookean<dim> material(c10, nu);
    const MaterialPoint<dim>         point(material);
    Tensor<2, dim>                   inverted, flat, not_a_number;
    inverted[0][0]     = -2.; // J = −1
    flat[0][0]         = -1.; // J = 0
    not_a_number[0][0] = std::nan("");
    for (const auto &[grad_u, name] : {std::make_pair(inverted, std::string("J = -1")),
                                       std::make_pair(flat, std::string("J = 0")),
                                       std::make_pair(not_a_number, std::string("J = nan"))})
      {
        const std::string message =
            exception_message<Materials::InadmissibleState>([&]() { point.evaluate(grad_u); });
        check(message.find("J = det F") != std::string::npos &&
                  message.find("admissible range") != std::string::npos,
              std::to_string(dim) + "D " + name + " throws InadmissibleState naming J",
              message.size());
      }
  }

  void
  test_parameters()
  {
    ParameterHandler prm;
    declare_and_choose_model<3>(prm, "neo-Hookean");
    const auto model = Materials::create<3>(prm);
    // defaults C10 = 100, ν = 0.4: E = 2 · 200 · 1.4
    check(model->is_finite_strain() && std::abs(model->youngs_modulus() - 560.) < 1e-12 &&
              std::abs(model->poissons_ratio() - 0.4) < 1e-15 && model->n_history() == 0,
          "registered as 'neo-Hookean' with defaults C10 = 100, nu = 0.4 (E)",
          model->youngs_modulus());

    for (const auto &[c, n, entry] :
         {std::make_tuple(0., 0.4, std::string("Material/neo-Hookean/C10")),
          std::make_tuple(100., 0.5, std::string("Material/neo-Hookean/Poisson's ratio"))})
      {
        const std::string message =
            exception_message<InputError>([&]() { Materials::NeoHookean<2>(c, n); });
        check(message.find(entry) == 0, "InputError naming " + entry, message.size());
      }
  }
} // namespace

int
main()
{
  test_finite_differences<2>();
  test_finite_differences<3>();
  test_objectivity<2>();
  test_objectivity<3>();
  test_small_strain_limit<2>();
  test_small_strain_limit<3>();
  test_plane_strain();
  test_inadmissible<2>();
  test_inadmissible<3>();
  test_parameters();
  return summary();
}
