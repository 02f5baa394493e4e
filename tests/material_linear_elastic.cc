// Linear elastic material: stress against finite differences of the strain
// energy, tangent against finite differences of the stress, and a closed-form
// uniaxial plane-strain state.

#include <stabilized_lagrangian/materials/linear_elastic.h>

#include "material_test_tools.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <random>

using namespace dealii;
using namespace StabilizedLagrangian;

namespace
{
  using namespace MaterialTestTools;

  template <int dim>
  void
  test_finite_differences()
  {
    const Materials::LinearElastic<dim> material(200000., 0.3);
    std::mt19937                        rng(42 + dim);
    const double                        eps = 1e-6;
    for (unsigned int sample = 0; sample < 5; ++sample)
      {
        const Tensor<2, dim> grad_u    = random_gradient<dim>(rng, 1e-2);
        const Tensor<2, dim> direction = random_gradient<dim>(rng, 1.);
        const auto           evaluate  = [&](const Tensor<2, dim> &g) {
          return material.evaluate(g, ArrayView<const double>(), ArrayView<double>());
        };
        const auto energy = [&](const Tensor<2, dim> &g) {
          return 0.5 * scalar_product(evaluate(g).stress, g);
        };
        const auto response = evaluate(grad_u);

        // stress = ∂W/∂∇u
        const double dW =
            (energy(grad_u + eps * direction) - energy(grad_u - eps * direction)) / (2. * eps);
        const double stress_error =
            std::abs(dW - scalar_product(response.stress, direction)) / std::abs(dW);
        check(stress_error < 1e-7,
              std::to_string(dim) + "D stress vs dW (relative error)",
              stress_error);

        // tangent = ∂σ/∂∇u
        const Tensor<2, dim> fd = (evaluate(grad_u + eps * direction).stress -
                                   evaluate(grad_u - eps * direction).stress) /
                                  (2. * eps);
        const Tensor<2, dim> exact = double_contract<2, 0, 3, 1>(response.tangent, direction);
        const double         tangent_error = (fd - exact).norm() / exact.norm();
        check(tangent_error < 1e-7,
              std::to_string(dim) + "D tangent vs dσ (relative error)",
              tangent_error);
      }
  }

  void
  test_closed_form()
  {
    // plane strain with σ_yy = 0: ε_xx = e, ε_yy = −ν/(1−ν) e
    const double                      E = 200000., nu = 0.3, e = 1e-3;
    const Materials::LinearElastic<2> material(E, nu);
    Tensor<2, 2>                      grad_u;
    grad_u[0][0]        = e;
    grad_u[1][1]        = -nu / (1. - nu) * e;
    const auto response = material.evaluate(grad_u, ArrayView<const double>(), ArrayView<double>());
    const double expected_xx = E / (1. - nu * nu) * e;
    check(std::abs(response.stress[0][0] - expected_xx) < 1e-9 * expected_xx,
          "plane strain sigma_xx against E/(1-nu^2) e",
          response.stress[0][0]);
    check(std::abs(response.stress[1][1]) < 1e-9 * expected_xx,
          "plane strain sigma_yy = 0",
          response.stress[1][1]);
    check(std::abs(response.out_of_plane_stress - nu * expected_xx) < 1e-9 * expected_xx,
          "plane strain sigma_zz = nu sigma_xx",
          response.out_of_plane_stress);
  }
} // namespace

int
main()
{
  test_finite_differences<2>();
  test_finite_differences<3>();
  test_closed_form();
  return summary();
}
