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
     * same triangulation; only its degrees of freedom on Γc are kept.
     */
    template <int dim> class FEPair
    {
    public:
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
      virtual unsigned int
      displacement_degree() const = 0;

      /** @brief Polynomial degree of the multiplier, for the contact quadrature. */
      virtual unsigned int
      multiplier_degree() const = 0;

      /**
       * @brief Whether the multiplier lives on the contact mesh coarsened once
       * (the parents of the contact faces) rather than on the contact faces.
       */
      virtual bool
      multiplier_on_coarser_mesh() const
      {
        return false;
      }
    };

    /** @brief The registry of FE pairs for dimension @p dim. */
    template <int dim> using Registry = PluginRegistry<FEPair<dim>>;
  } // namespace Discretization
} // namespace StabilizedLagrangian
