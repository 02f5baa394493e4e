#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <stabilized_lagrangian/materials/material.h>

#include <algorithm>
#include <functional>
#include <string>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    using namespace dealii;

    /**
     * @brief Deformation gradient F = I + ∇u in 3D; in plane strain (dim = 2)
     * F_33 = 1 and F_α3 = F_3α = 0.
     */
    template <int dim>
    Tensor<2, 3>
    deformation_gradient(const Tensor<2, dim> &grad_u)
    {
      Tensor<2, 3> F = embed_in_3d(grad_u);
      for (unsigned int i = 0; i < 3; ++i)
        F[i][i] += 1.;
      return F;
    }

    /**
     * @brief J = det F; throws InadmissibleState naming @p model if J is not
     * a positive number.
     */
    double
    admissible_jacobian(const Tensor<2, 3> &F, const std::string &model);

    /**
     * @brief Isotropic tensor function Y(X) = Σ_a y(x_a) n_a ⊗ n_a of a
     * symmetric tensor X = Σ_a x_a n_a ⊗ n_a (for instance exp or ln).
     * @param X symmetric tensor
     * @param y scalar function applied to the eigenvalues of @p X
     */
    SymmetricTensor<2, 3>
    isotropic_function(const SymmetricTensor<2, 3> &X, const std::function<double(double)> &y);

    /**
     * @brief Logarithm ln X of a symmetric positive definite tensor and its
     * derivative ∂ ln X / ∂X.
     */
    struct TensorLogarithm
    {
      /** ln X. */
      SymmetricTensor<2, 3> value;
      /**
       * ∂ ln X / ∂X for symmetric increments, in the eigenbasis of X
       * (de Souza Neto, Perić & Owen, appendix A):
       * L = Σ_a (1/x_a) E_a ⊗ E_a
       *   + Σ_{a≠b} θ_ab ½(n_a⊗n_b⊗n_a⊗n_b + n_a⊗n_b⊗n_b⊗n_a),
       * θ_ab = (ln x_a − ln x_b)/(x_a − x_b), whose limit 1/x_a for
       * x_b → x_a is reached without cancellation (see the .cc).
       */
      SymmetricTensor<4, 3> derivative;
    };

    /**
     * @brief ln X and ∂ ln X / ∂X by the spectral decomposition of X.
     * @param X symmetric positive definite tensor
     */
    TensorLogarithm
    tensor_logarithm(const SymmetricTensor<2, 3> &X);
  } // namespace Materials
} // namespace StabilizedLagrangian
