#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/lac/full_matrix.h>

#include <stabilized_lagrangian/materials/material.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace StabilizedLagrangian
{
  namespace Materials
  {
    using namespace dealii;

    /**
     * @brief The volume change a point of a cell keeps under `Volumetric
     * formulation = F-bar` or `mixed` (doc/formulation.md, "Near
     * incompressibility"): v = J = det F in finite strain, v = tr ∇u in small
     * strain, projected onto a discontinuous space of degree 0 or 1.
     *
     * - F-bar: v at the cell's centre (one sample, degree 0).
     * - mixed: the L² projection of v onto P_k(cell) from the quadrature points
     *   (the samples, weighted by JxW): the three-field Hu–Washizu formulation
     *   of Simo, Taylor & Pister (CMAME 51, 1985) with pressure and dilatation
     *   in P_k, condensed cell by cell. Its stationarity in the pressure gives
     *   θ = Π_k J, in the dilatation p = Π_k ∂W/∂θ, so the condensed weak form
     *   is the displacement one with F̄ = (Π_k J / J)^(1/d) F.
     *
     * P_1 is spanned by 1 and the reference coordinates ξ − ξ_c about the
     * reference cell's centre ξ_c.
     */
    template <int dim> class VolumeProjection
    {
    public:
      static constexpr unsigned int max_basis = dim + 1;

      VolumeProjection(const unsigned int degree,
                       const Point<dim>  &reference_centre,
                       const bool         finite)
          : degree(degree)
          , reference_centre(reference_centre)
          , finite(finite)
      {
        Assert(degree <= 1, ExcNotImplemented());
      }

      /** @brief The number of basis functions of the projection space. */
      unsigned int
      n_basis() const
      {
        return degree == 0 ? 1 : dim + 1;
      }

      /** @brief Basis function @p a at the reference point @p unit. */
      double
      basis(const unsigned int a, const Point<dim> &unit) const
      {
        return a == 0 ? 1. : unit[a - 1] - reference_centre[a - 1];
      }

      /** @brief v at one point: det F, or tr ∇u in small strain. */
      double
      volume_change(const Tensor<2, dim> &grad_u) const
      {
        return finite ? determinant(unit_symmetric_tensor<dim>() + grad_u) : trace(grad_u);
      }

      /** @brief ∂v/∂∇u: the cofactor J F⁻ᵀ, or I in small strain. */
      Tensor<2, dim>
      volume_change_derivative(const Tensor<2, dim> &grad_u) const
      {
        if (!finite)
          return unit_symmetric_tensor<dim>();
        const Tensor<2, dim> F = unit_symmetric_tensor<dim>() + grad_u;
        return determinant(F) * transpose(invert(F));
      }

      /**
       * @brief The projection for one cell from its samples: reference points
       * @p units, weights @p weights (JxW; any positive value for one sample)
       * and displacement gradients @p gradients there.
       */
      void
      reinit(const std::vector<Point<dim>>     &units,
             const std::vector<double>         &weights,
             const std::vector<Tensor<2, dim>> &gradients)
      {
        const unsigned int n_samples = units.size(), n = n_basis();
        // G = M⁻¹ Ψ W with M = Ψ W Ψᵀ: the coefficients are G v
        FullMatrix<double> mass(n, n);
        projector.reinit(n, n_samples);
        for (unsigned int k = 0; k < n_samples; ++k)
          for (unsigned int a = 0; a < n; ++a)
            {
              projector(a, k) = basis(a, units[k]) * weights[k];
              for (unsigned int b = 0; b < n; ++b)
                mass(a, b) += basis(a, units[k]) * basis(b, units[k]) * weights[k];
            }
        mass.gauss_jordan();
        FullMatrix<double> product(n, n_samples);
        mass.mmult(product, projector);
        projector = product;
        sample_derivatives.resize(n_samples);
        coefficient_values.fill(0.);
        for (unsigned int k = 0; k < n_samples; ++k)
          {
            const double v        = volume_change(gradients[k]);
            sample_derivatives[k] = volume_change_derivative(gradients[k]);
            for (unsigned int a = 0; a < n; ++a)
              coefficient_values[a] += projector(a, k) * v;
          }
      }

      /** @brief The coefficients of the projected v (for a cache). */
      const std::array<double, max_basis> &
      coefficients() const
      {
        return coefficient_values;
      }

      /** @brief The projected v at @p unit from @p coefficients. */
      double
      value(const std::array<double, max_basis> &coefficients, const Point<dim> &unit) const
      {
        double result = 0.;
        for (unsigned int a = 0; a < n_basis(); ++a)
          result += basis(a, unit) * coefficients[a];
        return result;
      }

      /** @brief The projected v at @p unit after reinit(). */
      double
      value(const Point<dim> &unit) const
      {
        return value(coefficient_values, unit);
      }

      /**
       * @brief ∂(projected v at @p unit)/∂∇u at sample @p k: a weight times
       * sample_derivative(k).
       */
      double
      sample_weight(const Point<dim> &unit, const unsigned int k) const
      {
        double result = 0.;
        for (unsigned int a = 0; a < n_basis(); ++a)
          result += basis(a, unit) * projector(a, k);
        return result;
      }

      /** @brief ∂v/∂∇u at sample @p k. */
      const Tensor<2, dim> &
      sample_derivative(const unsigned int k) const
      {
        return sample_derivatives[k];
      }

    private:
      const unsigned int            degree;
      const Point<dim>              reference_centre;
      const bool                    finite;
      FullMatrix<double>            projector;
      std::vector<Tensor<2, dim>>   sample_derivatives;
      std::array<double, max_basis> coefficient_values{};
    };

    /**
     * @brief The modified kinematics at one quadrature point (`Volumetric
     * formulation = F-bar` or `mixed`; doc/formulation.md, "Near
     * incompressibility"), given the volume change v̄ the point keeps
     * (VolumeProjection).
     *
     * Finite strain (de Souza Neto, Perić, Dutko, Owen, IJSS 33, 1996): the
     * model sees F̄ = α F, α = (v̄/J)^(1/3), in 3D; the weak form
     * ∫ J σ(F̄) : ∇ₓδu dv reads ∫ P̃ : ∇δu dV with P̃ = α⁻² P(F̄).
     *
     * Small strain (Hughes, IJNME 15, 1980, B-bar): the model sees
     * ∇ū = ∇u + (v̄ − tr ∇u)/3 I, whose trace is v̄.
     *
     * In plane strain both act on the 3D gradient (F₃₃ = 1): F̄₃₃ = α, ε̄₃₃ =
     * (v̄ − tr ∇u)/3. The isochoric part of F̄ is then that of F, as in the
     * three-field formulation of Simo, Taylor & Pister, and a point cannot
     * lose its in-plane area without straining its isochoric part (with the
     * in-plane α = (v̄/J)^(1/2) an in-plane collapse would cost no isochoric
     * energy).
     *
     * The derivatives of the weak-form stress with respect to ∇u at the point
     * and to v̄ give the consistent (non-symmetric) tangent.
     */
    template <int dim> class FBar
    {
    public:
      FBar(const Tensor<2, dim> &grad_u, const double kept_volume_change, const bool finite)
          : finite(finite)
          , kept(kept_volume_change)
      {
        modified = embed_in_3d(grad_u);
        if (!finite)
          {
            const double shift = (kept - trace(modified)) / 3.;
            for (unsigned int d = 0; d < 3; ++d)
              modified[d][d] += shift;
            return;
          }
        F = modified;
        for (unsigned int d = 0; d < 3; ++d)
          F[d][d] += 1.;
        const double J = determinant(F);
        if (!(J > 0.) || !(kept > 0.))
          throw InadmissibleState("Volumetric formulation: det F = " + std::to_string(J) +
                                  " at a quadrature point, " + std::to_string(kept) +
                                  " kept by the cell (must be > 0)");
        alpha    = std::cbrt(kept / J);
        modified = alpha * F - unit_symmetric_tensor<3>();
      }

      /** @brief The 3D displacement gradient the material sees. */
      const Tensor<2, 3> &
      modified_gradient() const
      {
        return modified;
      }

      /**
       * @brief From the material's @p response at the modified gradient
       * (Interface::evaluate_3d): the weak-form stress and its derivative with
       * respect to ∇u at the point in @p weak (with the out-of-plane Cauchy
       * stress σ₃₃(F̄) in plane strain), and its derivative with respect to the
       * kept volume change v̄ in @p d_kept.
       */
      void
      weak_form(const Response<3> &response, Response<dim> &weak, Tensor<2, dim> &d_kept) const
      {
        const Tensor<4, 3> &A = response.tangent;
        Tensor<2, 3>        stress, by_kept;
        Tensor<4, 3>        d_point;
        if (!finite)
          {
            // ∂σ/∂∇u (I − I⊗I/3) at the point, (A : I)/3 for v̄
            stress = response.stress;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                {
                  for (unsigned int e = 0; e < 3; ++e)
                    by_kept[a][b] += A[a][b][e][e] / 3.;
                  for (unsigned int c = 0; c < 3; ++c)
                    for (unsigned int e = 0; e < 3; ++e)
                      d_point[a][b][c][e] = A[a][b][c][e] - (c == e ? by_kept[a][b] : 0.);
                }
            weak.out_of_plane_stress = dim == 2 ? response.stress[2][2] : 0.;
          }
        else
          {
            // P̃ = α⁻² P̄ with ∂α/∂F = −α F⁻ᵀ/3, ∂α/∂v̄ = α/(3 v̄):
            // ∂P̃/∂F = α⁻¹ [A − (A:F) ⊗ F⁻ᵀ/3] + 2/3 α⁻² P̄ ⊗ F⁻ᵀ
            // ∂P̃/∂v̄ = [α⁻¹ (A:F)/3 − 2/3 α⁻² P̄] / v̄
            const double       scale_P = 1. / (alpha * alpha);
            const double       scale_A = 1. / alpha;
            const Tensor<2, 3> F_inv_T = transpose(invert(F));
            stress                     = scale_P * response.stress;
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                {
                  const double volumetric = scale_A * scalar_product(A[a][b], F) / 3.;
                  const double geometric  = 2. / 3. * scale_P * response.stress[a][b];
                  by_kept[a][b]           = (volumetric - geometric) / kept;
                  for (unsigned int c = 0; c < 3; ++c)
                    for (unsigned int e = 0; e < 3; ++e)
                      d_point[a][b][c][e] =
                          scale_A * A[a][b][c][e] + (geometric - volumetric) * F_inv_T[c][e];
                }
            // σ̄ = P̄ F̄ᵀ / det F̄, det F̄ = v̄
            weak.out_of_plane_stress = dim == 2 ? response.stress[2] * (alpha * F[2]) / kept : 0.;
          }
        weak.stress  = in_plane_block<dim>(stress);
        weak.tangent = in_plane_block<dim>(d_point);
        d_kept       = in_plane_block<dim>(by_kept);
      }

    private:
      const bool   finite;
      const double kept;
      Tensor<2, 3> F, modified;
      double       alpha = 1.;
    };
  } // namespace Materials
} // namespace StabilizedLagrangian
