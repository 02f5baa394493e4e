#include <deal.II/base/symmetric_tensor.h>

#include <stabilized_lagrangian/contact/pairing.h>

namespace StabilizedLagrangian
{
  namespace Contact
  {
    namespace
    {
      /**
       * The first coordinate axis e_d with |n_d| < 0.7: t_0 from it is well
       * conditioned (|e_d − (e_d·n) n| > 0.71), and the choice changes only
       * where a component of n crosses 0.7 (45° from an axis). The least
       * aligned axis would be as well conditioned but jumps between e_x and
       * e_y wherever |n_x| = |n_y|, e.g. everywhere on a nearly flat deformable
       * surface with n ≈ e_z: the tangent basis then turns by 90° between two
       * Newton iterates and the components of Λ mean another direction.
       * (One of the components is below 1/√3 for a unit n.)
       */
      template <int dim>
      Tensor<1, dim>
      least_aligned_axis(const Tensor<1, dim> &n)
      {
        unsigned int axis = 0;
        while (axis + 1 < dim && std::abs(n[axis]) >= 0.7)
          ++axis;
        Tensor<1, dim> e;
        e[axis] = 1.;
        return e;
      }
    } // namespace

    template <int dim>
    std::array<Tensor<1, dim>, dim - 1>
    tangent_basis(const Tensor<1, dim> &n)
    {
      std::array<Tensor<1, dim>, dim - 1> t;
      if constexpr (dim == 2)
        {
          t[0][0] = n[1];
          t[0][1] = -n[0];
        }
      else
        {
          const Tensor<1, dim> e = least_aligned_axis(n);
          t[0]                   = e - (e * n) * n;
          t[0] /= t[0].norm();
          t[1] = cross_product_3d(n, t[0]);
        }
      return t;
    }

    template <int dim>
    std::array<Tensor<2, dim>, dim - 1>
    tangent_basis_derivative(const Tensor<1, dim> &n)
    {
      std::array<Tensor<2, dim>, dim - 1> d;
      if constexpr (dim == 2)
        {
          // t = (n_1, −n_0)
          d[0][0][1] = 1.;
          d[0][1][0] = -1.;
        }
      else
        {
          // t_0 = a/|a| with a = e − (e·n) n, t_1 = n × t_0; e is the fixed axis
          // of tangent_basis(), so the derivative holds away from its switches
          const Tensor<1, dim> e      = least_aligned_axis(n);
          const Tensor<1, dim> a      = e - (e * n) * n;
          const double         a_norm = a.norm();
          const Tensor<1, dim> t0     = a / a_norm;
          // ∂a_i/∂n_j = −n_i e_j − (e·n) δ_ij
          const Tensor<2, dim> identity = unit_symmetric_tensor<dim>();
          const Tensor<2, dim> da       = -outer_product(n, e) - (e * n) * identity;
          d[0]                          = (identity - outer_product(t0, t0)) * da / a_norm;
          // ∂(n × t_0)_i/∂n_j = ε_ijl t0_l + ε_ikl n_k ∂t0_l/∂n_j
          for (unsigned int j = 0; j < dim; ++j)
            {
              Tensor<1, dim> ej, dt0;
              ej[j] = 1.;
              for (unsigned int l = 0; l < dim; ++l)
                dt0[l] = d[0][l][j];
              const Tensor<1, dim> column = cross_product_3d(ej, t0) + cross_product_3d(n, dt0);
              for (unsigned int i = 0; i < dim; ++i)
                d[1][i][j] = column[i];
            }
        }
      return d;
    }

    template std::array<Tensor<1, 2>, 1>
    tangent_basis<2>(const Tensor<1, 2> &);
    template std::array<Tensor<1, 3>, 2>
    tangent_basis<3>(const Tensor<1, 3> &);
    template std::array<Tensor<2, 2>, 1>
    tangent_basis_derivative<2>(const Tensor<1, 2> &);
    template std::array<Tensor<2, 3>, 2>
    tangent_basis_derivative<3>(const Tensor<1, 3> &);
  } // namespace Contact
} // namespace StabilizedLagrangian
