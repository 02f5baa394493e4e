#pragma once

#include <deal.II/base/tensor.h>

#include <stabilized_lagrangian/materials/material.h>

#include <cmath>
#include <string>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    using namespace dealii;

    /**
     * @brief The F-bar kinematics at one quadrature point (`Volumetric
     * formulation = F-bar`; doc/formulation.md, "Near incompressibility").
     *
     * Finite strain (de Souza Neto, Perić, Dutko, Owen, IJSS 33, 1996): the
     * model sees F̄ = α F, α = (J₀/J)^(1/d), whose volume change J₀ = det F₀
     * is that of the cell's centre; the weak form ∫ J σ(F̄) : ∇ₓδu dv reads
     * ∫ P̃ : ∇δu dV with P̃ = α^(1−d) P(F̄). d = dim: in plane strain F₃₃ = 1
     * and only the in-plane part carries the volume change.
     *
     * Small strain (Hughes, IJNME 15, 1980, B-bar): the model sees
     * ∇ū = ∇u + (tr ∇u₀ − tr ∇u)/d I, whose trace (the volume change) is
     * that of the cell's centre.
     *
     * The derivatives of the weak-form stress with respect to ∇u at the point
     * and to ∇u₀ at the centre give the consistent (non-symmetric) tangent.
     */
    template <int dim> class FBar
    {
    public:
      FBar(const Tensor<2, dim> &grad_u, const Tensor<2, dim> &centre_grad_u, const bool finite)
          : finite(finite)
      {
        if (!finite)
          {
            modified           = grad_u;
            const double shift = (trace(centre_grad_u) - trace(grad_u)) / dim;
            for (unsigned int d = 0; d < dim; ++d)
              modified[d][d] += shift;
            return;
          }
        F              = unit_symmetric_tensor<dim>() + grad_u;
        F0             = unit_symmetric_tensor<dim>() + centre_grad_u;
        const double J = determinant(F), J0 = determinant(F0);
        if (!(J > 0.) || !(J0 > 0.))
          throw InadmissibleState("F-bar: det F = " + std::to_string(J) +
                                  " at a quadrature point, " + std::to_string(J0) +
                                  " at the cell's centre (must be > 0)");
        alpha    = std::pow(J0 / J, 1. / dim);
        modified = alpha * F - unit_symmetric_tensor<dim>();
      }

      /** @brief The displacement gradient the material sees. */
      const Tensor<2, dim> &
      modified_gradient() const
      {
        return modified;
      }

      /**
       * @brief From the material's @p response at the modified gradient: the
       * weak-form stress, and its derivatives with respect to ∇u at the point
       * (@p d_point) and at the cell's centre (@p d_centre).
       */
      void
      weak_form(const Response<dim> &response,
                Tensor<2, dim>      &stress,
                Tensor<4, dim>      &d_point,
                Tensor<4, dim>      &d_centre) const
      {
        const Tensor<4, dim> &A = response.tangent;
        if (!finite)
          {
            // ∂σ/∂∇u (I − I⊗I/d) at the point, ∂σ/∂∇u I⊗I/d at the centre
            stress = response.stress;
            Tensor<2, dim> volumetric; // A : I
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                for (unsigned int e = 0; e < dim; ++e)
                  volumetric[a][b] += A[a][b][e][e];
            for (unsigned int a = 0; a < dim; ++a)
              for (unsigned int b = 0; b < dim; ++b)
                for (unsigned int c = 0; c < dim; ++c)
                  {
                    d_centre[a][b][c][c] = volumetric[a][b] / dim;
                    for (unsigned int e = 0; e < dim; ++e)
                      d_point[a][b][c][e] = A[a][b][c][e] - d_centre[a][b][c][e];
                  }
            return;
          }
        // P̃ = α^(1−d) P̄ with ∂α/∂F = −α F⁻ᵀ/d, ∂α/∂F₀ = α F₀⁻ᵀ/d:
        // ∂P̃/∂F  = α^(2−d) [A − (A:F) ⊗ F⁻ᵀ/d] + (d−1)/d α^(1−d) P̄ ⊗ F⁻ᵀ
        // ∂P̃/∂F₀ = α^(2−d) (A:F) ⊗ F₀⁻ᵀ/d − (d−1)/d α^(1−d) P̄ ⊗ F₀⁻ᵀ
        const double         scale_P = std::pow(alpha, 1. - dim);
        const double         scale_A = std::pow(alpha, 2. - dim);
        const Tensor<2, dim> F_inv_T = transpose(invert(F)), F0_inv_T = transpose(invert(F0));
        Tensor<2, dim>       A_F;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            A_F[a][b] = scalar_product(A[a][b], F);
        stress = scale_P * response.stress;
        for (unsigned int a = 0; a < dim; ++a)
          for (unsigned int b = 0; b < dim; ++b)
            {
              const double volumetric = scale_A * A_F[a][b] / dim;
              const double geometric  = (dim - 1.) / dim * scale_P * response.stress[a][b];
              for (unsigned int c = 0; c < dim; ++c)
                for (unsigned int e = 0; e < dim; ++e)
                  {
                    d_point[a][b][c][e] =
                        scale_A * A[a][b][c][e] + (geometric - volumetric) * F_inv_T[c][e];
                    d_centre[a][b][c][e] = (volumetric - geometric) * F0_inv_T[c][e];
                  }
            }
      }

    private:
      const bool     finite;
      Tensor<2, dim> F, F0, modified;
      double         alpha = 1.;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
