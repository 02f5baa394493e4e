#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <array>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    using namespace dealii;

    /**
     * @brief A rigid motion x = c + d + R (X − c) of a rigid obstacle: the
     * translation d of its centre c and the rotation R about it; the identity
     * by default.
     */
    template <int dim> struct RigidMotion
    {
      Point<dim>     centre;
      Tensor<1, dim> translation;
      Tensor<2, dim> rotation = unit_symmetric_tensor<dim>();

      /** @brief Where the motion takes the point @p X of the obstacle at rest. */
      Point<dim>
      apply(const Point<dim> &X) const
      {
        return centre + translation + rotation * (X - centre);
      }

      /** @brief The point of the obstacle at rest that the motion takes to @p x. */
      Point<dim>
      inverse(const Point<dim> &x) const
      {
        return centre + transpose(rotation) * (x - centre - translation);
      }
    };

    /**
     * @brief Pairing of a slave point with the contact partner (doc/formulation.md,
     * "Signs and notation").
     *
     * The closest point x²(ξ) on the partner's surface, the unit normal n there
     * pointing out of the partner, and dim−1 unit tangents completing an
     * orthonormal basis. The gap of a slave position x is g_n = (x − x²)·n.
     */
    template <int dim> struct Pairing
    {
      Point<dim>                          master_point;
      Tensor<1, dim>                      normal;
      std::array<Tensor<1, dim>, dim - 1> tangents;
      /**
       * ∂n/∂x and ∂t_α/∂x at the slave position: how the pairing moves with the
       * slave point, which the generalized Newton linearises (zero for a plane).
       */
      Tensor<2, dim>                      normal_gradient;
      std::array<Tensor<2, dim>, dim - 1> tangent_gradients;
      /**
       * With a deformable master (Contact::MasterSurface): the master face and
       * the reference point ξ on it. The pairing freezes ξ, n and t_α; the master
       * point x²(ξ) follows the master's displacement. −1 for a rigid obstacle.
       */
      int            master_face = -1;
      Point<dim - 1> master_reference_point;
      /**
       * With a moving rigid obstacle: its position when the pairing was made
       * or last followed (Partner::follow() moves x², n and t_α by the motion
       * since).
       */
      RigidMotion<dim> partner_motion;
      /**
       * With a deformable master, at ξ in the configuration of the pairing
       * (Partner::follow()): the surface tangents τ_a = ∂x²/∂ξ_a, the second
       * derivatives ∂²x²/∂ξ_a∂ξ_b and the surface gradient ∂Δu²/∂ξ_a of the
       * master's step increment: what the linearised pairing needs
       * (doc/formulation.md, "Two deformable bodies").
       */
      std::array<Tensor<1, dim>, dim - 1>                      surface_tangents;
      std::array<std::array<Tensor<1, dim>, dim - 1>, dim - 1> surface_curvature;
      std::array<Tensor<1, dim>, dim - 1>                      increment_gradient;

      /** @brief Gap g_n = (x − x²)·n of a slave position x with this pairing frozen. */
      double
      gap(const Point<dim> &x) const
      {
        return (x - master_point) * normal;
      }

      /** @brief Components of a vector in the tangent basis, (t_α · v). */
      Tensor<1, dim - 1>
      tangential_components(const Tensor<1, dim> &v) const
      {
        Tensor<1, dim - 1> components;
        for (unsigned int a = 0; a < dim - 1; ++a)
          components[a] = tangents[a] * v;
        return components;
      }

      /** @brief The vector Σ_α c_α t_α of tangent-basis components @p c. */
      Tensor<1, dim>
      from_tangential_components(const Tensor<1, dim - 1> &c) const
      {
        Tensor<1, dim> v;
        for (unsigned int a = 0; a < dim - 1; ++a)
          v += c[a] * tangents[a];
        return v;
      }
    };

    /**
     * @brief Orthonormal tangents completing the unit normal @p n.
     */
    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n);

    /**
     * @brief ∂t_α/∂n of tangent_basis() (entry [α][i][j] = ∂t_α,i/∂n_j), for the
     * chain rule ∂t_α/∂x = ∂t_α/∂n · ∂n/∂x.
     */
    template <int dim>
    std::array<Tensor<2, dim>, dim - 1>
    tangent_basis_derivative(const Tensor<1, dim> &n);
  } // namespace Contact
} // namespace StabilizedLagrangian
