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
     * @brief Copy of the components of @p t whose indices are all below
     * min(dim_from, dim_to), the others zero: the plane-strain (dim = 2)
     * quantities seen in 3D and back.
     */
    template <int dim_to, int rank, int dim_from>
    Tensor<rank, dim_to>
    common_block(const Tensor<rank, dim_from> &t)
    {
      constexpr int        dim = std::min(dim_from, dim_to);
      Tensor<rank, dim_to> result;
      for (unsigned int c = 0; c < Tensor<rank, dim>::n_independent_components; ++c)
        {
          const TableIndices<rank> indices = Tensor<rank, dim>::unrolled_to_component_indices(c);
          result[indices]                  = t[indices];
        }
      return result;
    }

    /**
     * @brief The 3D tensor whose leading dim×dim block is @p t, the other
     * components zero: the displacement gradient of plane strain (u_3 = 0,
     * ∂/∂x_3 = 0) seen in 3D.
     */
    template <int dim>
    Tensor<2, 3>
    embed_in_3d(const Tensor<2, dim> &t)
    {
      return common_block<3>(t);
    }

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
     * @brief The leading dim×dim (×dim×dim) block of a 3D tensor: in plane
     * strain the in-plane stress, and the tangent with the out-of-plane
     * components of the displacement gradient held at zero.
     */
    template <int dim, int rank>
    Tensor<rank, dim>
    in_plane_block(const Tensor<rank, 3> &t)
    {
      return common_block<dim>(t);
    }

    /**
     * @brief Response of a model computed in 3D, for dimension @p dim: the
     * in-plane blocks of the stress and tangent, and in plane strain the
     * out-of-plane Cauchy stress.
     * @param stress first Piola–Kirchhoff (Cauchy in small strain) stress in 3D
     * @param tangent ∂stress/∂F in 3D
     * @param cauchy_stress_33 Cauchy σ_33, used when dim = 2
     */
    template <int dim>
    Response<dim>
    response_from_3d(const Tensor<2, 3> &stress,
                     const Tensor<4, 3> &tangent,
                     const double        cauchy_stress_33)
    {
      Response<dim> response;
      response.stress              = in_plane_block<dim>(stress);
      response.tangent             = in_plane_block<dim>(tangent);
      response.out_of_plane_stress = (dim == 2) ? cauchy_stress_33 : 0.;
      return response;
    }

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
