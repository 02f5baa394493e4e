#pragma once

#include <deal.II/fe/fe.h>

#include <stabilized_lagrangian/plugins.h>

namespace StabilizedLagrangian
{
  namespace Discretization
  {
    using namespace dealii;

    /**
     * @brief A pair of finite element spaces: displacement in the bodies and
     * multipliers (λ_n and Λ together) on the contact boundary only
     * (doc/formulation.md, "Unknowns and spaces").
     *
     * The multiplier element is a face element (FE_TraceQ, FE_FaceQ) on the
     * same triangulation, or on simplices a continuous P_k field of the whole
     * mesh (deal.II has no trace element for them); only its degrees of
     * freedom on Γc are kept.
     */
    template <int dim> class FEPair
    {
    public:
      FEPair(const unsigned int displacement_degree, const unsigned int multiplier_degree)
          : u_degree(displacement_degree)
          , m_degree(multiplier_degree)
      {
      }

      virtual ~FEPair() = default;

      /** @brief Vector-valued element of the displacement (dim components). */
      virtual std::unique_ptr<FiniteElement<dim>>
      displacement_element() const = 0;

      /**
       * @brief Element of the multipliers with @p n_components components:
       * λ_n first, then the dim−1 components of Λ when there is friction.
       */
      virtual std::unique_ptr<FiniteElement<dim>>
      multiplier_element(const unsigned int n_components) const = 0;

      /** @brief Polynomial degree of the displacement, for the quadrature. */
      unsigned int
      displacement_degree() const
      {
        return u_degree;
      }

      /** @brief Polynomial degree of the multiplier, for the contact quadrature. */
      unsigned int
      multiplier_degree() const
      {
        return m_degree;
      }

      /**
       * @brief Whether the multiplier lives on the contact mesh coarsened once
       * (the parents of the contact faces) rather than on the contact faces.
       */
      virtual bool
      multiplier_on_coarser_mesh() const
      {
        return false;
      }

      /**
       * @brief Whether the multiplier basis is the dual (biorthogonal) one:
       * on each contact face ψ_j = Σ_k A_jk φ_k with A = D M⁻¹ (M the face's
       * multiplier mass matrix, D its row sums), so ∫_F ψ_j φ_k = δ_jk ∫_F φ_j
       * and the global multiplier mass matrix ∫ψ_j φ_k is diagonal
       * (doc/formulation.md, "Dual multipliers").
       */
      virtual bool
      dual_multiplier() const
      {
        return false;
      }

      /** @brief Whether the pair is for triangles / tetrahedra (P_k) rather than Q_k cells. */
      virtual bool
      simplex() const
      {
        return false;
      }

    protected:
      const unsigned int u_degree, m_degree;
    };

    /** @brief The registry of FE pairs for dimension @p dim. */
    template <int dim> using Registry = PluginRegistry<FEPair<dim>>;
  } // namespace Discretization
} // namespace StabilizedLagrangian
